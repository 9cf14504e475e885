#!/usr/bin/env bash
# The first run of a new user, timed: clone this repository's current commit into a temporary
# directory and run `bash scripts/main.sh` there (install the run-time dependencies, build `kimp`,
# run the default wall-height study), without ccache. Prints each phase's wall time (clone,
# dependencies, configure, build, study), the machine's cores and load before and after, and the
# build's CPU time and its ten most expensive steps (each step's user + system time, recorded by
# bench/step_cpu.sh as the compiler and linker launcher), and the CPU time of main.sh's processes
# (on a shared machine, CPU time / cores estimates the wall time on idle cores). With the dependencies installed, the install phase
# only checks them (and installs gui/'s npm packages into the clone, from npm's cache).
# Usage: bench/fresh_clone.sh [KEEP_DIR]   (KEEP_DIR: clone there and keep it; default: a
#        temporary directory, removed at the end). Goal: <= 6 min on 2 cores.
#   KIMP_RECORDS_DIR (default: ../shared/data/records beside this repository) reaches the study.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
commit="$(git -C "$root" rev-parse HEAD)"
[[ -x /usr/bin/time ]] || { echo "fresh_clone.sh: needs /usr/bin/time (Debian package time)" >&2; exit 1; }
if [[ $# -gt 0 ]]; then
  work="$1"
  mkdir -p "$work"
else
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
export KIMP_RECORDS_DIR="${KIMP_RECORDS_DIR:-$root/../shared/data/records}"
# A fresh machine has no compiler cache. The launcher only records each step's CPU time.
unset CMAKE_C_COMPILER_LAUNCHER KIMP_BUILD_DIR KIMP_TARGETS
export CCACHE_DISABLE=1
export CMAKE_CXX_COMPILER_LAUNCHER="$root/bench/step_cpu.sh"
export CMAKE_CXX_LINKER_LAUNCHER="$root/bench/step_cpu.sh"
export KIMP_STEP_CPU_LOG="$work/steps.cpu"
: > "$KIMP_STEP_CPU_LOG"

load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "fresh_clone: commit ${commit:0:12}, $(nproc) cores, load $(load) (1, 5, 15 min)"
start="$EPOCHREALTIME"
git clone --quiet "$root" "$work/kimp"
git -C "$work/kimp" checkout --quiet "$commit"
cloned="$EPOCHREALTIME"

# Every line of main.sh's output with the seconds since the start of main.sh.
log="$work/main.log"
main_start="$EPOCHREALTIME"
set +e
(cd "$work/kimp" &&
  /usr/bin/time -o "$work/main.cpu" -f "%U %S" bash scripts/main.sh "$work/kimp/out/study" 2>&1) |
  while IFS= read -r line; do
    printf '%s %s\n' "$(awk -v a="$main_start" -v b="$EPOCHREALTIME" 'BEGIN{printf "%.1f", b - a}')" "$line"
  done > "$log"
status=${PIPESTATUS[0]}
set -e
end="$EPOCHREALTIME"
if [[ $status -ne 0 || ! -f "$work/kimp/out/study/report.md" ]]; then
  tail -30 "$log" >&2
  echo "fresh_clone: scripts/main.sh failed (exit $status); log above" >&2
  exit 1
fi

# Phase boundaries: the first line of CMake's configure, CMake's last configure line, the last
# build step, the end. A phase that printed nothing takes 0 s.
at() { awk -v pattern="$1" '$0 ~ pattern {print $1; exit}' "$log"; }
configure_start=$(at ' -- |The CXX compiler')
build_start=$(at 'Build files have been written')
study_start=$(awk '/\[[0-9]+\/[0-9]+\] (Building|Linking|Generating|Running)/ {t = $1} END {print t}' "$log")
total=$(awk -v a="$main_start" -v b="$end" 'BEGIN{printf "%.1f", b - a}')
configure_start=${configure_start:-0}
build_start=${build_start:-$configure_start}
study_start=${study_start:-$build_start}
steps=$(grep -cE '\[[0-9]+/[0-9]+\] (Building|Linking|Generating|Running)' "$log" || true)
printf "%-34s %7.1f s\n" "clone" "$(awk -v a="$start" -v b="$cloned" 'BEGIN{print b - a}')"
printf "%-34s %7.1f s\n" "dependencies (install-deps runtime)" "$configure_start"
printf "%-34s %7.1f s\n" "configure (cmake)" "$(awk -v a="$configure_start" -v b="$build_start" 'BEGIN{print b - a}')"
printf "%-34s %7.1f s  (%d steps, -j%s)\n" "build (kimp, kimp-fem)" \
  "$(awk -v a="$build_start" -v b="$study_start" 'BEGIN{print b - a}')" "$steps" "$(nproc)"
printf "%-34s %7.1f s\n" "study (kimp study)" "$(awk -v a="$study_start" -v b="$total" 'BEGIN{print b - a}')"
printf "%-34s %7.1f s  (%.2f min)\n" "total: clone to study written" \
  "$(awk -v a="$start" -v b="$end" 'BEGIN{print b - a}')" \
  "$(awk -v a="$start" -v b="$end" 'BEGIN{print (b - a) / 60}')"
# CPU time of main.sh and every process it started: on a shared machine, the wall time an idle
# machine of these cores would need is about this over the cores (the build runs -j cores).
cpu=$(awk '{printf "%.0f", $1 + $2}' "$work/main.cpu")
printf "%-34s %7d s  (user + system; / %d cores = %.1f min)\n" "cpu time of scripts/main.sh" \
  "$cpu" "$(nproc)" "$(awk -v c="$cpu" -v n="$(nproc)" 'BEGIN{print c / n / 60}')"
echo "load after: $(load)"
build_cpu=$(awk '{s += $1} END {printf "%.0f", s}' "$KIMP_STEP_CPU_LOG")
printf "%-34s %7d s  (%d compile and link steps; / %d cores = %.1f min)\n" "cpu time of the build" \
  "$build_cpu" "$(wc -l < "$KIMP_STEP_CPU_LOG")" "$(nproc)" \
  "$(awk -v c="$build_cpu" -v n="$(nproc)" 'BEGIN{print c / n / 60}')"
echo "most expensive build steps (CPU s):"
sort -rn "$KIMP_STEP_CPU_LOG" | head -10 | awk '{printf "%8.1f  %s\n", $1, $2}'
