#!/usr/bin/env bash
# Opening a large result in `kimp gui`: the run of tests/gui/big_result_scene.yaml (24 storeys, six
# impact laws, histories every 5 ms; about 17 MB of results JSON) made through the server, then
# opened RUNS times from the Runs tab in headless Chromium (tests/gui/gui_big_result_test.js
# --opens RUNS: click to charts drawn, the first open's phases as the progress indicator showed
# them), and GET /api/runs/ID/data fetched RUNS times by curl offering gzip, deflate and br as a
# browser does (server time to the first byte, total time, bytes and Content-Encoding).
# Prints the median and best of each.
# Usage: bench/gui_open_result.sh [BUILD_DIR (default: build)] [RUNS (default: 5)]
#   KIMP_CHROMIUM (default: chromium on the PATH): the browser; node and gui/node_modules
#   (puppeteer-core) as for the browser tests (scripts/install-deps.sh).
set -euo pipefail
source "$(dirname "$0")/lib.sh"
bench_init gui_open_result.sh 5 "$@"
bench_require
chromium="${KIMP_CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}"
[[ -x "$chromium" && -x "$(command -v node)" && -d "$root/gui/node_modules/puppeteer-core" ]] ||
  { echo "gui_open_result.sh: needs node, Chromium (KIMP_CHROMIUM) and gui/node_modules/puppeteer-core" \
      "(scripts/install-deps.sh)" >&2; exit 1; }
command -v curl > /dev/null || { echo "gui_open_result.sh: needs curl" >&2; exit 1; }
bench_workdir

# median_best FILE: "median X ms  best Y ms" of the numbers in FILE, one a line.
median_best() {
  local n
  n=$(wc -l < "$1")
  printf "median %6.0f ms  best %6.0f ms" "$(sort -g "$1" | sed -n "$(((n + 1) / 2))p")" "$(sort -g "$1" | head -1)"
}

echo "kimp gui: opening a large result, $runs opens ($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
KIMP_CHROMIUM="$chromium" node "$root/tests/gui/gui_big_result_test.js" "$kimp" "$work" --opens "$runs" \
  > "$work/browser.log" 2>&1 || { cat "$work/browser.log" >&2; exit 1; }
grep -E '^(open of|  +[0-9]+ ms:)' "$work/browser.log"
sed -n -E 's/^open of .*: ([0-9]+) ms$/\1/p; s/^open [0-9]+: ([0-9]+) ms$/\1/p' "$work/browser.log" > "$work/opens"
echo "browser, click to charts drawn:        $(median_best "$work/opens")"

# The server's part: the same run's data by curl, from a kimp gui on the test's runs folder.
runs_dir="$work/gui_big_result_runs"
runs_found=("$runs_dir"/*-lumped)
id="$(basename "${runs_found[0]}")"
"$kimp" gui --port 0 --runs-dir "$runs_dir" > "$work/gui.out" 2>&1 &
server=$!
trap 'kill "$server" 2> /dev/null; rm -rf "$work"' EXIT
url=""
for _ in $(seq 100); do
  url="$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/gui.out" || true)"
  [[ -n "$url" ]] && break
  sleep 0.1
done
[[ -n "$url" ]] || { echo "gui_open_result.sh: kimp gui did not start: $(cat "$work/gui.out")" >&2; exit 1; }
: > "$work/first_byte"
: > "$work/total"
for ((i = 0; i < runs; ++i)); do
  curl -s -o /dev/null -D "$work/headers" -H 'Accept-Encoding: gzip, deflate, br' \
    -w '%{time_starttransfer} %{time_total} %{size_download}\n' "${url}api/runs/$id/data" > "$work/curl"
  read -r first total bytes < "$work/curl"
  awk -v t="$first" 'BEGIN { printf "%.1f\n", t * 1000 }' >> "$work/first_byte"
  awk -v t="$total" 'BEGIN { printf "%.1f\n", t * 1000 }' >> "$work/total"
done
encoding="$(tr -d '\r' < "$work/headers" | sed -n 's/^[Cc]ontent-[Ee]ncoding: //p')"
echo "GET /api/runs/ID/data: $bytes bytes, Content-Encoding: ${encoding:-none}"
echo "  server, request to first byte:       $(median_best "$work/first_byte")"
echo "  whole response:                      $(median_best "$work/total")"
