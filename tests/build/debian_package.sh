#!/usr/bin/env bash
# `cpack` makes a Debian package whose dependencies apt can resolve here, and whose files, taken
# out of it, run: the program on its installed scene and `import scatterlab` from its
# dist-packages. (Installing it for real changes the machine: `apt install ./scatterlab_*.deb`
# was tried on a fresh Debian 12, see CHANGELOG.)
# Usage: debian_package.sh BUILD_DIR
set -uo pipefail
build=$(realpath "$1")
source "$(dirname "$0")/../cli/harness.sh"

if (cd "$build" && cpack -B "$work/package") >"$work/cpack.log" 2>&1; then pass; else
  fail "cpack: $(tail -3 "$work/cpack.log")"
  report "debian package"
  exit 1
fi
deb=$(ls "$work"/package/scatterlab_*.deb)
fields=$(dpkg-deb --field "$deb" Package Version Architecture Depends)
for expected in "Package: scatterlab" "Version: $("$build/sim/scatterlab" --version | awk '{print $NF}')" \
                "Architecture: $(dpkg --print-architecture)" "python3-numpy" "python3-h5py" "libhdf5"; do
  if grep -q -- "$expected" <<<"$fields"; then pass; else fail "control fields lack '$expected': $fields"; fi
done
# What apt would do to install it: every dependency resolves from Debian's packages.
if apt-get install -s "$deb" >"$work/apt.log" 2>&1 && grep -q "^Inst scatterlab " "$work/apt.log"
then pass; else fail "apt-get install -s: $(tail -3 "$work/apt.log")"; fi

root=$work/root
dpkg-deb -x "$deb" "$root"
exe=$root/usr/bin/scatterlab
if "$exe" simulate "$root/usr/share/scatterlab/scenes/paper-beam.toml" --photons 2000 --batches 4 \
     --out beam.h5 >"$work/run.log" 2>&1 && "$exe" info beam.h5 | grep -q "photons run 2000"; then
  pass
else
  fail "the packaged program on the packaged scene: $(tail -3 "$work/run.log")"
fi
site=$(ls -d "$root"/usr/lib/python3*/dist-packages)
if PYTHONPATH=$site /usr/bin/python3 -c "
import scatterlab
assert scatterlab.__file__.startswith('$site'), scatterlab.__file__
r = scatterlab.simulate(photons=2000, batches=4, radiance=False)
assert r.tallies['fluence'].mean.size > 0
" >"$work/python.log" 2>&1; then pass; else fail "import scatterlab from the package: $(tail -3 "$work/python.log")"; fi
report "debian package"
