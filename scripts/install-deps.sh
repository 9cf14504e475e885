#!/usr/bin/env bash
# The single list of Debian packages kimp needs (build, tests, charts).
# Non-interactive and idempotent; run as root (or with sudo) on Debian 12.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git clang-format
  libdeal.ii-dev            # brings Trilinos, p4est, OpenMPI
  libgmsh-dev gmsh
  libeigen3-dev
  libhdf5-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  openmpi-bin
  python3 python3-matplotlib python3-numpy python3-h5py
  pybind11-dev python3-dev python3-pytest python3-yaml  # the Python module `kimp` and its tests
  jupyter-nbconvert python3-nbformat python3-nbclient python3-ipykernel  # the example notebook, run in CI
  libcpp-httplib-dev                        # the embedded web server of `kimp gui`
  chromium                                  # headless browser tests of the web interface
  nodejs                                    # gui/ page code: lint, npm packages, browser tests
)

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "install-deps: done"
fi

# npm packages of gui/ (uPlot and js-yaml, embedded into kimp at build time; ESLint for the
# gui_lint test; puppeteer-core for the browser tests), exact versions from gui/package-lock.json. The system Chromium is used: no browser is
# downloaded. Debian's nodejs may come without npm (NodeSource's includes it).
if ! command -v npm >/dev/null 2>&1; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get install -y -qq --no-install-recommends npm >/dev/null
fi
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PUPPETEER_SKIP_DOWNLOAD=1 npm ci --prefix "$repo/gui" --no-audit --no-fund
echo "install-deps: npm packages of gui/ installed"
