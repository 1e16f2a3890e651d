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
         "$prefix/share/doc/scatterlab/README.md" "$prefix/share/doc/scatterlab/notebooks" \
         "$data/explore/index.html" "$data/explore/node_modules/plotly.js-dist-min/plotly.min.js"; do
  if [ -e "$f" ]; then pass; else fail "not installed: ${f#"$prefix"/}"; fi
done
if [ "$("$exe" --version)" = "$("$build/sim/scatterlab" --version)" ]; then pass; else fail "installed --version"; fi
if "$exe" simulate "$data/scenes/paper-beam.toml" --photons 2000 --batches 4 --out beam.h5 \
     >"$work/run.log" 2>&1 && "$exe" info beam.h5 | grep -q "photons run 2000"; then
  pass
else
  fail "installed simulate on the installed scene: $(tail -3 "$work/run.log")"
fi
# The installed explorer serves the installed page (not the source tree's) on a free port and
# ends cleanly on SIGINT.
"$exe" explore --port 0 >"$work/explore.log" 2>&1 &
explorer=$!
for _ in $(seq 50); do grep -q "http://" "$work/explore.log" && break; sleep 0.1; done
url=$(grep -o "http://[^ ]*" "$work/explore.log" | head -1)
if [ -n "$url" ] && grep -q "the page: $data/explore" "$work/explore.log" &&
   /usr/bin/python3 -c 'import sys, urllib.request
assert b"scatterlab explore" in urllib.request.urlopen(sys.argv[1], timeout=10).read()' "$url"; then
  pass
else
  fail "the installed explorer: $(cat "$work/explore.log")"
fi
kill -INT "$explorer"
if wait "$explorer"; then pass; else fail "the installed explorer did not end cleanly on SIGINT"; fi
# The Python module (when this build has it), from the prefix alone, reads the file the installed
# program wrote.
module=$(find "$prefix/lib" -path "*-packages/scatterlab/__init__.py" 2>/dev/null | head -1)
if [ ! -d "$build/python/scatterlab" ]; then
  echo "no Python module in this build: not checked"
elif [ -z "$module" ]; then
  fail "the Python module is not installed under $prefix/lib"
elif (cd "$work" && PYTHONPATH=$(dirname "$(dirname "$module")") /usr/bin/python3 -c '
import scatterlab, sys
assert scatterlab.__file__.startswith(sys.argv[1]), scatterlab.__file__
assert scatterlab.open("beam.h5").tallies["fluence"].mean.shape == (15, 40)
' "$prefix") >"$work/python.log" 2>&1; then
  pass
else
  fail "the installed module: $(tail -3 "$work/python.log")"
fi
report "install prefix"
