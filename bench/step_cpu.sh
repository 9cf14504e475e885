#!/usr/bin/env bash
# Compiler and linker launcher that records the CPU time (user + system, s) of each build step:
# appends "<seconds> <output file>" to $KIMP_STEP_CPU_LOG, then exits with the step's status.
# bench/fresh_clone.sh configures the clone's build with it; by hand:
#   cmake -B build -DCMAKE_CXX_COMPILER_LAUNCHER=$PWD/bench/step_cpu.sh \
#     -DCMAKE_CXX_LINKER_LAUNCHER=$PWD/bench/step_cpu.sh ...
#   KIMP_STEP_CPU_LOG="$PWD/build/step-cpu.log" ninja -C build kimp
# On a shared machine the wall time of a step says little; its CPU time is what it costs.
output=""
previous=""
for argument in "$@"; do
  [[ "$previous" == "-o" ]] && output="$argument"
  previous="$argument"
done
times="$(mktemp)"
/usr/bin/time -o "$times" -f "%U %S" "$@"
status=$?
if [[ -n "${KIMP_STEP_CPU_LOG:-}" ]]; then
  awk -v out="$output" 'END { printf "%.2f %s\n", $1 + $2, out }' "$times" >> "$KIMP_STEP_CPU_LOG"
fi
rm -f "$times"
exit $status
