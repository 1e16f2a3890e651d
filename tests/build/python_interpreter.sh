#!/usr/bin/env bash
# The Python module is built for the interpreter a user names: a virtual environment made from
# Debian's python3 with --system-site-packages, given as -DPython_EXECUTABLE or
# -DPython3_EXECUTABLE, is the one CMake configures the module for (the build is then the same
# code; tests/python/test_interpreter.py runs the module from such an environment).
# Usage: python_interpreter.sh SOURCE_DIR
set -uo pipefail
source_dir=$1
source "$(dirname "$0")/../cli/harness.sh"

/usr/bin/python3 -m venv --without-pip --system-site-packages "$work/venv" || fail "venv"
python=$work/venv/bin/python
for spelling in Python_EXECUTABLE Python3_EXECUTABLE; do
  build=$work/build-$spelling
  if cmake -S "$source_dir" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -D$spelling="$python" \
       -DSCATTERLAB_BUILD_TESTS=OFF -DSCATTERLAB_BUILD_BENCH=OFF >"$work/$spelling.log" 2>&1 &&
     grep -q "Python module: $python, pybind11" "$work/$spelling.log"; then
    pass
  else
    fail "-D$spelling=$python: $(grep -m2 "Python module" "$work/$spelling.log")"
  fi
done
report "python interpreter"
