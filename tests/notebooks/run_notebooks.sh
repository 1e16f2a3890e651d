#!/usr/bin/env bash
# Usage: run_notebooks.sh SCATTERLAB SOURCE_DIR
# Makes small data with the scatterlab program, then executes every notebook in notebooks/ top to
# bottom, headless, against it. Executed copies go to a temporary folder: outputs are never
# written back into the source tree. A notebook may write down what its figure holds in
# $SCATTERLAB_FIGURE_CHECKS, checked at the end: fluence_curves must show, for both point-source
# runs, the exact, diffusion and Grosjean curves that simulate writes beside the Monte Carlo.
set -euo pipefail
exe=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
data=$work/data
checks=$work/figure-checks
mkdir -p "$data" "$checks"

"$exe" simulate --albedo 0.5 --g 0.9 --photons 2e5 --batches 16 --theta-bins 9 --phi-bins 12 \
  --out "$data/paper-beam.h5" >/dev/null
"$exe" fit "$data/paper-beam.h5" >/dev/null
mkdir -p "$data/sweep"
for medium in "0.5 0.5" "0.9 0.9"; do
  set -- $medium
  "$exe" simulate --albedo "$1" --g "$2" --photons 2e5 --batches 16 --theta-bins 9 --phi-bins 12 \
    --out "$data/sweep/albedo=$1_g=$2.h5" >/dev/null
done
"$exe" fit "$data/sweep" --models adexp_ridge >/dev/null
"$exe" searchlight --albedo 0.9 --g 0.5 --eta 1.33 --photons 1e5 --batches 16 --r-bins 50 \
  --out "$data/searchlight.h5" >/dev/null
mkdir -p "$data/render-study"
"$exe" render --study --quick --out "$data/render-study" \
  "$source_dir/data/scenes/bumpy-sphere.toml" "$source_dir/data/scenes/tile.toml" >/dev/null
"$exe" simulate "$source_dir/data/scenes/lit-sphere.toml" --albedo 0.9 --g 0.5 --photons 2e5 \
  --batches 16 --out "$data/lit-sphere.h5" >/dev/null
"$exe" simulate "$source_dir/data/scenes/lit-mesh.toml" --photons 2e5 --batches 16 \
  --out "$data/lit-mesh.h5" >/dev/null
for material in regular_milk orange_juice_powder; do
  for channel in red green blue; do
    "$exe" searchlight "$source_dir/data/scenes/oblique-beam.toml" --material "$material" \
      --channel "$channel" --photons 1e5 --batches 16 \
      --out "$data/oblique-$material-$channel.h5" >/dev/null
  done
done
for albedo in 0.3 0.9; do
  "$exe" simulate --source point --albedo "$albedo" --g 0 --photons 5e4 --batches 16 \
    --out "$data/point-$albedo.h5" >/dev/null
done

failures=0
for notebook in "$source_dir"/notebooks/*.ipynb; do
  name=$(basename "$notebook")
  if SCATTERLAB_DATA=$data SCATTERLAB_FIGURE_CHECKS=$checks MPLBACKEND=Agg \
      PYDEVD_DISABLE_FILE_VALIDATION=1 \
      /usr/bin/python3 -m nbconvert --to notebook --execute --ExecutePreprocessor.timeout=300 \
      --output-dir "$work/executed" "$notebook" >"$work/log" 2>&1; then
    echo "ok: $name"
  else
    echo "FAIL: $name"
    cat "$work/log"
    failures=$((failures + 1))
  fi
done

# The point-source figure: two runs, each with its three model curves on both panels.
if /usr/bin/python3 - "$checks/fluence_curves.json" <<'EOF_CHECK'; then
import json, sys
shown = json.load(open(sys.argv[1]))
assert shown["runs"] == 2, shown
for label in ["exact transport", "classical diffusion", "Grosjean"]:
    assert label in shown["legend"], shown["legend"]
for panel, curves in shown["model_curves"].items():
    assert curves == sorted(["diffusion", "exact", "grosjean"] * 2), (panel, curves)
assert len(shown["model_curves"]) == 2, shown
EOF_CHECK
  echo "ok: fluence_curves figure holds the model curves"
else
  echo "FAIL: fluence_curves figure lacks the exact, diffusion or Grosjean curves"
  failures=$((failures + 1))
fi
exit "$failures"
