#!/usr/bin/env bash
# The README's test command: install dependencies, build, run the whole test suite.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh" all
# The tests and benchmarks on (main.sh configures the same build directory without them); the
# browser tests are required here: a missing node or Chromium fails the configure step.
bash "$root/scripts/build.sh" -DBUILD_TESTING=ON -DKIMP_BUILD_BENCH=ON -DKIMP_REQUIRE_BROWSER_TESTS=ON
# mpirun as root (CI and fresh machines run as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
ctest --test-dir "${KIMP_BUILD_DIR:-$root/build}" --output-on-failure -j "$(nproc)" "$@"
