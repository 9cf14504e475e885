#!/usr/bin/env bash
# The README's main command: install dependencies, build, and run the end-to-end wall-height study
# on its embedded defaults (mesh -> FEM -> fitted k_imp -> building response, charts, report).
# Output goes to ./out/study (or the first argument). Run from the repository root so that the
# shared strong-motion records (../shared/data/records) are found when present.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/out/study}"
# Only what the study needs at run time: the test-only packages (GoogleTest, Chromium, Jupyter,
# pytest, ESLint, ...) are installed by scripts/test.sh.
bash "$root/scripts/install-deps.sh" runtime
# Only the `kimp` executable, configured without the tests and benchmarks (scripts/test.sh
# switches them on again).
KIMP_TARGETS=kimp bash "$root/scripts/build.sh" -DBUILD_TESTING=OFF -DKIMP_BUILD_BENCH=OFF
cd "$root"
"${KIMP_BUILD_DIR:-$root/build}/kimp" study data/scenes/wall_height_study.yaml -o "$out"
echo "kimp: study written to $out (report: $out/report.md)"
