#!/usr/bin/env bash
# Sets up, builds and runs every test: the Release suite (unit, physics, CLI), then the fast
# tests again under AddressSanitizer and UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh build
(cd build && ctest --output-on-failure -j "$(nproc)")
scripts/build.sh build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DSCATTERLAB_SANITIZE=ON -DSCATTERLAB_BUILD_BENCH=OFF
(cd build-sanitize && ctest --output-on-failure -L fast -j "$(nproc)")
