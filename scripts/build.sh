#!/usr/bin/env bash
# Configures and builds scatterlab.
# Usage: scripts/build.sh [--target NAME] [BUILD_DIR [extra cmake args…]]
# Release by default; pass -DSCATTERLAB_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug for ASan/UBSan.
# --target builds only NAME (and what it needs), as scripts/run.sh does with the program.
set -euo pipefail
cd "$(dirname "$0")/.."
target=()
if [ "${1:-}" = --target ]; then target=(--target "$2"); shift 2; fi
build_dir=${1:-build}
shift || true
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build_dir" -j "$(nproc)" "${target[@]}"
