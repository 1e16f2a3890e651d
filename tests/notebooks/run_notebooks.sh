#!/usr/bin/env bash
# Usage: run_notebooks.sh SCATTERLAB SOURCE_DIR
# Executes every notebook in notebooks/ top to bottom, headless, as a new user opens it: each with
# an empty $SCATTERLAB_DATA folder of its own, so that its first cell makes its own small data
# (with the Python module on $PYTHONPATH, or the program SCATTERLAB for what only the program
# runs: meshes, the render study, the fit of a sweep directory). Then searchlight_profiles once
# more, on a file the program made in mm, whose figures must say mm. Executed copies go to a
# temporary folder: outputs are never written back into the source tree. A notebook may write down
# what its figure holds in $SCATTERLAB_FIGURE_CHECKS, checked at the end: fluence_curves must
# show, for both point-source runs, the exact, diffusion and Grosjean curves that simulate writes
# beside the Monte Carlo; searchlight_profiles must label its axes in the file's length unit.
set -euo pipefail
exe=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
checks=$work/figure-checks
mkdir -p "$checks" "$checks/mm"
export SCATTERLAB_PROGRAM=$exe MPLBACKEND=Agg PYDEVD_DISABLE_FILE_VALIDATION=1

failures=0
# execute NOTEBOOK DATA CHECKS: runs it against the data folder DATA.
execute() {
  local name start
  name=$(basename "$1")
  start=$SECONDS
  if SCATTERLAB_DATA=$2 SCATTERLAB_FIGURE_CHECKS=$3 \
      /usr/bin/python3 -m nbconvert --to notebook --execute --ExecutePreprocessor.timeout=300 \
      --output-dir "$work/executed" "$1" >"$work/log" 2>&1; then
    echo "ok: $name (data: ${2#"$work"/}, $((SECONDS - start)) s)"
  else
    echo "FAIL: $name (data: ${2#"$work"/}, $((SECONDS - start)) s)"
    cat "$work/log"
    failures=$((failures + 1))
  fi
}

# Every notebook from nothing: the folder is empty, and whatever it needs it makes.
for notebook in "$source_dir"/notebooks/*.ipynb; do
  data=$work/data-$(basename "$notebook" .ipynb)
  mkdir -p "$data"
  execute "$notebook" "$data" "$checks"
  if [ -z "$(ls -A "$data")" ]; then
    echo "FAIL: $(basename "$notebook") made no data in its empty folder"
    failures=$((failures + 1))
  fi
done

# A file made beforehand by the program, in mm (a measured material): read, not remade.
mkdir -p "$work/program-mm"
"$exe" searchlight --material regular_milk --channel green --photons 1e5 --batches 16 \
  --r-bins 50 --out "$work/program-mm/searchlight.h5" >/dev/null 2>&1
before=$(stat -c %y "$work/program-mm/searchlight.h5")
execute "$source_dir/notebooks/searchlight_profiles.ipynb" "$work/program-mm" "$checks/mm"
if [ "$(stat -c %y "$work/program-mm/searchlight.h5")" != "$before" ]; then
  echo "FAIL: searchlight_profiles remade a file it was given"
  failures=$((failures + 1))
fi

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

# The searchlight figures: every length in the file's unit, mfp for the notebook's own run and
# mm for the material's, and never the other.
for case in "$checks/searchlight_profiles.json mfp mm" "$checks/mm/searchlight_profiles.json mm mfp"; do
  set -- $case
  if /usr/bin/python3 - "$1" "$2" "$3" <<'EOF_CHECK'; then
import json, sys
shown = json.load(open(sys.argv[1]))
unit, other = sys.argv[2], sys.argv[3]
assert shown["length_unit"] == unit, shown["length_unit"]
xlabels = [label for label in shown["labels"] if label.startswith("r (")]
assert xlabels and all(label == f"r ({unit})" for label in xlabels), shown["labels"]
assert all(other not in label for label in shown["labels"]), shown["labels"]
assert all(f" {unit}$^{{" in label for label in shown["labels"] if label not in xlabels), \
    shown["labels"]
EOF_CHECK
    echo "ok: searchlight_profiles labels a file in $2 in $2"
  else
    echo "FAIL: searchlight_profiles labels a file in $2 otherwise"
    failures=$((failures + 1))
  fi
done
exit "$failures"
