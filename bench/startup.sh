#!/usr/bin/env bash
# Whole-process cost of kimp: `kimp --version`, `kimp lumped` on a 1 s record (the default
# building between walls, synthetic motion trimmed to 1 s) and `kimp lumped` on the 48 s Kobe
# record with walls at dt 2e-5 s (thesis Table 4.3's building, one case, 2.4 million steps; only
# when the record is found), each run RUNS times. Prints per case the median and best wall time
# (ms), the median user + system CPU time, the maximum resident set size, and the number of
# shared libraries each executable loads. The outputs are written to a fresh directory each run.
# Usage: bench/startup.sh [BUILD_DIR (default: build)] [RUNS (default: 20)]
#   KIMP_RECORDS_DIR (default: ../shared/data/records beside the repository): the Kobe record.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init startup.sh 20 "$@"
bench_require time
bench_workdir
cat > "$work/one_second.yaml" <<'EOF'
# The default building between walls under the synthetic record trimmed to 1 s.
ground_motion:
  record: synthetic
  duration: "1 s"
EOF
# Thesis Table 4.3 (data/scenes/table_4_3_kobe_gap15.yaml) as one case: modified Kelvin-Voigt.
sed -e '/^cases:/,$d' -e 's/companion: true/companion: false/' \
  "$root/data/scenes/table_4_3_kobe_gap15.yaml" > "$work/kobe_48s.yaml"

# measure NAME COMMAND...: RUNS runs; one line of statistics. Wall time from bash's clock (µs),
# CPU time and memory from /usr/bin/time (10 ms resolution for the CPU time).
measure() {
  local name="$1"
  shift
  local log="$work/$name.times" walls="$work/$name.walls"
  : > "$log"
  : > "$walls"
  for ((i = 0; i < runs; ++i)); do
    rm -rf "$work/out"
    local start="$EPOCHREALTIME"
    /usr/bin/time -a -o "$log" -f "%U %S %M" "$@" > /dev/null 2>&1
    local end="$EPOCHREALTIME"
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f\n", (b - a) * 1000 }' >> "$walls"
  done
  local n wall_med wall_best cpu_med rss_max
  n=$(wc -l < "$walls")
  wall_med=$(sort -g "$walls" | sed -n "$(((n + 1) / 2))p")
  wall_best=$(sort -g "$walls" | head -1)
  cpu_med=$(awk '{printf "%.0f\n", ($1 + $2) * 1000}' "$log" | sort -g | sed -n "$(((n + 1) / 2))p")
  rss_max=$(awk '{print $3}' "$log" | sort -g | tail -1)
  printf "%-34s wall median %7.1f ms  best %7.1f ms  cpu median %4d ms  max RSS %6.1f MiB\n" \
    "$name" "$wall_med" "$wall_best" "$cpu_med" "$(awk -v k="$rss_max" 'BEGIN{print k/1024}')"
}

echo "kimp start-up, $runs runs each ($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
for exe in kimp kimp-fem; do
  [[ -x "$build/$exe" ]] && echo "$exe: $(ldd "$build/$exe" | wc -l) shared libraries"
done
measure "kimp --version" "$kimp" --version
measure "kimp lumped (1 s record)" "$kimp" lumped "$work/one_second.yaml" -o "$work/out" -q
if [[ -f "$records/RSN1106_KOBE_KJM000.AT2" ]]; then
  measure "kimp lumped (48 s Kobe, dt 2e-5 s)" "$kimp" lumped "$work/kobe_48s.yaml" \
    -o "$work/out" -q --records-dir "$records"
else
  echo "kimp lumped (48 s Kobe): skipped, no $records/RSN1106_KOBE_KJM000.AT2 (set KIMP_RECORDS_DIR)"
fi
if [[ -x "$build/kimp-fem" ]]; then
  measure "kimp-fem --version" "$build/kimp-fem" --version
fi
