#!/usr/bin/env bash
# The single list of what kimp needs, in two groups:
#   install-deps.sh runtime   what scripts/main.sh needs: build `kimp` and run the study (charts,
#                             the page scripts embedded at build time)
#   install-deps.sh [all]     runtime plus what the tests, benchmarks, the Python module and the
#                             example notebook need (scripts/test.sh)
# Debian packages, then the npm packages of gui/. Non-interactive and idempotent; run as root (or
# with sudo) on Debian 12.
set -euo pipefail

group="${1:-all}"
case "$group" in
  runtime | all) ;;
  *)
    echo "install-deps: unknown group '$group' (expected runtime or all)" >&2
    exit 2
    ;;
esac

runtime=(
  build-essential cmake ninja-build pkg-config git
  libdeal.ii-dev            # brings Trilinos, p4est, OpenMPI
  libgmsh-dev gmsh
  libeigen3-dev
  libhdf5-dev               # the lean kimp's serial HDF5 (deal.II brings OpenMPI's)
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  openmpi-bin
  python3 python3-matplotlib python3-numpy python3-h5py  # the study's charts
  libcpp-httplib-dev                        # the embedded web server of `kimp gui`
  nodejs                                    # npm: uPlot and js-yaml, embedded at build time
)
tests=(
  clang-format                              # scripts/check-format.sh
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-dev python3-pytest python3-yaml  # the Python module `kimp` and its tests
  jupyter-nbconvert python3-nbformat python3-nbclient python3-ipykernel  # the example notebook, run in CI
  chromium                                  # headless browser tests of the web interface
  time                                      # /usr/bin/time: the whole-process timings of bench/
)
packages=("${runtime[@]}")
if [ "$group" = all ]; then packages+=("${tests[@]}"); fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps ($group): all ${#packages[@]} packages present"
else
  echo "install-deps ($group): installing ${#missing[@]} packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "install-deps: done"
fi

# npm packages of gui/, exact versions from gui/package-lock.json: uPlot and js-yaml (embedded
# into kimp at build time) for every group; ESLint (the gui_lint test) and puppeteer-core (the
# browser tests) only for `all`. The system Chromium is used: no browser is downloaded. Debian's
# nodejs may come without npm (NodeSource's includes it).
if ! command -v npm >/dev/null 2>&1; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get install -y -qq --no-install-recommends npm >/dev/null
fi
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "$group" = runtime ]; then
  # Kept when a full install is already there (a test run's), so main.sh does not undo it.
  if [ -f "$repo/gui/node_modules/uplot/package.json" ] && [ -f "$repo/gui/node_modules/js-yaml/package.json" ]; then
    echo "install-deps: npm packages of gui/ present"
  else
    PUPPETEER_SKIP_DOWNLOAD=1 npm ci --prefix "$repo/gui" --omit=dev --no-audit --no-fund
    echo "install-deps: npm packages of gui/ installed (uPlot, js-yaml)"
  fi
else
  PUPPETEER_SKIP_DOWNLOAD=1 npm ci --prefix "$repo/gui" --no-audit --no-fund
  echo "install-deps: npm packages of gui/ installed"
fi
