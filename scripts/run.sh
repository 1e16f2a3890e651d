#!/usr/bin/env bash
# Sets up, builds (Release) and runs the main job on its built-in default: a pencil beam in an
# infinite medium with g = 0.9 and albedo 0.5 (Vavassori §4.1), written to out/paper-beam.h5.
# It installs and builds only the program and what it links; scripts/test.sh adds the rest (fit,
# render, explore, MPI, Python, the tests), and the program then has every command.
# Extra arguments go to `scatterlab simulate`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh core
scripts/build.sh --target scatterlab build
mkdir -p out
./build/sim/scatterlab simulate --out out/paper-beam.h5 "$@"
