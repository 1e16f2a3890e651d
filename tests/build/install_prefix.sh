#!/usr/bin/env bash
# `cmake --install` into a fresh prefix, then the installed program runs on its own: a scene
# from the installed data, its file read back by the installed `info`.
# Usage: install_prefix.sh BUILD_DIR
set -uo pipefail
build=$1
source "$(dirname "$0")/../cli/harness.sh"
prefix=$work/prefix

if cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1; then pass; else
  fail "cmake --install: $(tail -3 "$work/install.log")"
fi
exe=$prefix/bin/scatterlab
data=$prefix/share/scatterlab
for f in "$exe" "$data/scenes/paper-beam.toml" "$data/mcml/sample.mci" \
         "$prefix/share/doc/scatterlab/README.md" "$prefix/share/doc/scatterlab/notebooks"; do
  if [ -e "$f" ]; then pass; else fail "not installed: ${f#"$prefix"/}"; fi
done
if [ "$("$exe" --version)" = "$("$build/sim/scatterlab" --version)" ]; then pass; else fail "installed --version"; fi
if "$exe" simulate "$data/scenes/paper-beam.toml" --photons 2000 --batches 4 --out beam.h5 \
     >"$work/run.log" 2>&1 && "$exe" info beam.h5 | grep -q "photons run 2000"; then
  pass
else
  fail "installed simulate on the installed scene: $(tail -3 "$work/run.log")"
fi
report "install prefix"
