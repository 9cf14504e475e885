#!/usr/bin/env bash
# Whole-process start-up of kimp: `kimp --version` and `kimp lumped` on a 1 s record (the default
# building between walls, synthetic motion trimmed to 1 s), each run RUNS times; prints the
# median and best wall time, user + system CPU time and maximum resident set size, and the number
# of shared libraries each executable loads.
# Usage: bench/startup.sh [BUILD_DIR (default: build)] [RUNS (default: 20)]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
runs="${2:-20}"
kimp="$build/kimp"
[[ -x "$kimp" ]] || { echo "startup.sh: $kimp not found (build the target kimp)" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "startup.sh: needs /usr/bin/time (Debian package time)" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cat > "$work/one_second.yaml" <<'EOF'
# The default building between walls under the synthetic record trimmed to 1 s.
ground_motion:
  record: synthetic
  duration: "1 s"
EOF

# measure NAME COMMAND...: RUNS runs; one line of statistics.
measure() {
  local name="$1"
  shift
  local log="$work/$name.times"
  : > "$log"
  for ((i = 0; i < runs; ++i)); do
    rm -rf "$work/out"
    /usr/bin/time -a -o "$log" -f "%e %U %S %M" "$@" > /dev/null 2>&1
  done
  local n wall_med wall_best cpu_med rss_max
  n=$(wc -l < "$log")
  wall_med=$(awk '{print $1}' "$log" | sort -g | sed -n "$(((n + 1) / 2))p")
  wall_best=$(awk '{print $1}' "$log" | sort -g | head -1)
  cpu_med=$(awk '{printf "%.2f\n", $2 + $3}' "$log" | sort -g | sed -n "$(((n + 1) / 2))p")
  rss_max=$(awk '{print $4}' "$log" | sort -g | tail -1)
  printf "%-26s wall median %5.2f s  best %5.2f s  cpu median %5.2f s  max RSS %6.1f MiB\n" \
    "$name" "$wall_med" "$wall_best" "$cpu_med" "$(awk -v k="$rss_max" 'BEGIN{print k/1024}')"
}

echo "kimp start-up, $runs runs each ($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
for exe in kimp kimp-fem; do
  [[ -x "$build/$exe" ]] && echo "$exe: $(ldd "$build/$exe" | wc -l) shared libraries"
done
measure "kimp --version" "$kimp" --version
measure "kimp lumped (1 s record)" "$kimp" lumped "$work/one_second.yaml" -o "$work/out" -q
if [[ -x "$build/kimp-fem" ]]; then
  measure "kimp-fem --version" "$build/kimp-fem" --version
fi
