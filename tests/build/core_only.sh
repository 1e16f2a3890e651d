#!/usr/bin/env bash
# The core builds without any optional component: configured as on a machine that has none of
# Ceres, Embree, tinyobjloader, OpenEXR, libpng, MPI, cpp-httplib, nlohmann-json or muparser
# (CMake is told not to find them), it builds scatterlab, which runs simulate and searchlight,
# links none of those libraries, and answers fit, report, render and explore with one line saying
# what the build needs, exit status 2.
# Its Python module (pybind11 is not optional here: it is what the check runs) works the same way.
# Usage: core_only.sh SOURCE_DIR
set -uo pipefail
source_dir=$1
source "$(dirname "$0")/../cli/harness.sh"
build=$work/build
missing=(Ceres embree tinyobjloader OpenEXR PNG MPI PkgConfig nlohmann_json muparser)
disable=()
for package in "${missing[@]}"; do disable+=("-DCMAKE_DISABLE_FIND_PACKAGE_$package=TRUE"); done

# Unoptimised and without debug information: what is checked is that the core configures, builds,
# links and runs alone, which optimisation does not change, and -O0 compiles in a fraction of the
# time (CI runs this beside the other tests).
if cmake -S "$source_dir" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0 \
     -DCMAKE_C_FLAGS_DEBUG=-O0 "${disable[@]}" \
     >"$work/configure.log" 2>&1 &&
   cmake --build "$build" --target scatterlab scatterlab_python -j "$(nproc)" \
     >"$work/build.log" 2>&1; then
  pass
else
  fail "core-only build: $(grep -m3 -iE "error|not found" "$work/configure.log" "$work/build.log")"
  report "core-only build"
  exit 1
fi
if grep -q "components: fit OFF, render OFF, explore OFF, MPI OFF" "$work/configure.log"; then pass; else
  fail "the configure summary does not say every component is off"
fi
exe=$build/sim/scatterlab
linked=$(readelf -d "$exe" | grep NEEDED)  # the libraries it links itself
# Ceres is a static library on Debian: its code, or glog, which it brings, would show.
for library in libglog libembree libtinyobjloader libOpenEXR libpng libmpi libcpp-httplib libmuparser; do
  if grep -q "$library" <<<"$linked"; then fail "links $library"; else pass; fi
done
if nm -C "$exe" | grep -q "ceres::"; then fail "holds Ceres code"; else pass; fi
if "$exe" simulate --photons 2000 --batches 4 --out beam.h5 >/dev/null 2>&1 &&
   "$exe" searchlight --photons 2000 --batches 4 --out half.h5 >/dev/null 2>&1 &&
   "$exe" info half.h5 >/dev/null; then
  pass
else
  fail "simulate, searchlight or info failed in the core build"
fi
for command in fit report render explore; do
  status=0
  "$exe" "$command" beam.h5 --out anything >"$work/stdout" 2>"$work/stderr" || status=$?
  if [ "$status" -ne 2 ]; then
    fail "$command: exit status $status, not 2"
  elif [ "$(grep -c . "$work/stderr")" -ne 1 ] ||
       ! grep -q "no '$command' command.*Debian" "$work/stderr"; then
    fail "$command: not one line saying what the build needs: $(cat "$work/stderr")"
  elif [ -e anything ]; then
    fail "$command: wrote a file"
  else
    pass
  fi
done
# The help whole before grep reads it: grep -q stops at its match, and the program, still
# writing, would end on SIGPIPE (a failed pipeline under pipefail).
"$exe" --help >"$scratch/help.txt"
if grep -q "not in this build: it needs Ceres" "$scratch/help.txt"; then pass; else
  fail "--help does not say fit is not in this build"
fi
# The Python module of the core build runs and reads as the full one, and its fit says what the
# build needs, as the program's does.
if PYTHONPATH=$build/python /usr/bin/python3 -c '
import scatterlab
r = scatterlab.simulate(photons=2000, batches=4)
assert r.tallies["fluence"].mean.shape == (15, 40)
try:
    scatterlab.fit("beam.h5")
except ValueError as e:
    assert "no '"'"'fit'"'"' command" in str(e) and "libceres-dev" in str(e), e
else:
    raise AssertionError("fit ran without Ceres")
' >"$work/python.log" 2>&1; then
  pass
else
  fail "the core build's Python module: $(tail -3 "$work/python.log")"
fi
report "core-only build"
