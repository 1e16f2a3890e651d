#!/usr/bin/env bash
# Installs what scatterlab needs to build and test on Debian 12, and nothing that is already there.
# Idempotent: a second run installs nothing and prints nothing but its last line.
# Usage: scripts/setup.sh [core]
#   core: only what the program itself needs (scripts/run.sh): a compiler, CMake and the libraries
#   the core links. fit, render, explore, MPI, Python, the tests and the page come with no argument.
set -euo pipefail

core=(
  build-essential cmake ninja-build
  libeigen3-dev libhdf5-dev libfmt-dev libcli11-dev libtomlplusplus-dev librandom123-dev libhwy-dev
)
rest=(
  pkg-config libceres-dev libgtest-dev libgmock-dev libbenchmark-dev
  libopenmpi-dev openmpi-bin
  libembree-dev libtinyobjloader-dev libopenexr-dev libpng-dev
  clang-format
  python3-matplotlib  # the figures (sim/io/plot_figure.py) and the notebooks
  python3-h5py python3-h5netcdf python3-nbconvert python3-nbclient python3-ipykernel
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-xarray python3-pytest
  python3-tqdm  # progress="tqdm" in the Python module
  python3-venv  # the module from a virtual environment (tests/python/test_interpreter.py)
  python3-jsonschema  # scene files against `scatterlab scene --schema` (tests/cli/scene_schema.sh)
  mkdocs mkdocs-material  # the manual as a site (mkdocs.yml; tests/docs/site.sh)
  libcpp-httplib-dev nlohmann-json3-dev libmuparser-dev  # scatterlab explore
  chromium chromium-driver python3-selenium  # its page's test in a headless browser
  clang libclang-rt-14-dev libomp-dev  # scripts/fuzz.sh: libFuzzer, and OpenMP under clang
)
case "${1:-}" in
  core) packages=("${core[@]}") ;;
  "") packages=("${core[@]}" "${rest[@]}")
    # npm installs the page's JavaScript (web/package.json). Debian's npm comes with its nodejs; a
    # nodejs from elsewhere that already brings npm is left as it is.
    command -v npm >/dev/null 2>&1 || packages+=(nodejs npm) ;;
  *) echo "setup: unknown argument '$1': accepted are 'core' or nothing" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

if [ "${1:-}" = core ]; then echo "setup: the core's dependencies present"; exit 0; fi

# The page's libraries at the versions web/package-lock.json pins, when they are not there yet.
web="$(dirname "$0")/../web"
if [ ! -f "$web/node_modules/.package-lock.json" ] ||
   [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "setup: npm ci in web/"
  (cd "$web" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error >/dev/null)
fi
echo "setup: all dependencies present"
