#!/usr/bin/env bash
# Configure and build kimp (Release) into ./build. Extra arguments go to CMake's configure step.
# KIMP_BUILD_DIR overrides the build directory; KIMP_JOBS the parallel jobs (default: all cores);
# KIMP_TARGETS the targets to build (default: all, i.e. kimp, the tests and the benchmarks).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${KIMP_BUILD_DIR:-$root/build}"
jobs="${KIMP_JOBS:-$(nproc)}"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
        -DKIMP_WARNINGS_AS_ERRORS=ON "$@"
elif [ $# -gt 0 ]; then
  cmake "$build" "$@"
fi
targets=()
for t in ${KIMP_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" -j "$jobs" "${targets[@]}"
