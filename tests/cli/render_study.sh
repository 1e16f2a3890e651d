#!/usr/bin/env bash
# Usage: render_study.sh SCATTERLAB SOURCE_DIR
# `scatterlab render --study --quick` end to end: the output directory is made, the CSV has a row
# per scene, method and budget with finite errors and times (and pathtrace's z-scores against the
# path-traced reference, and the reference's noise), and the error plot and the side-by-side
# images are written.
set -u
exe=$1
source_dir=$2
source "$(dirname "$0")/harness.sh"
scenes=("$source_dir/data/scenes/bumpy-sphere.toml" "$source_dir/data/scenes/tile.toml")

# The output directory is made when missing, with its parents, as every command's --out DIR is.
if "$exe" render --study --quick --out "$work/new/study" "${scenes[@]}" >stdout 2>stderr; then
  pass
else
  fail "study: $(cat stderr)"
fi

csv="$work/new/study/render_study.csv"
if [ "$(head -1 "$csv" 2>/dev/null)" = "scene,method,budget,light_samples,seconds,rmse,relative_error,mean_z2,reference_noise,resolution" ]; then
  pass
else
  fail "CSV header: $(head -1 "$csv" 2>/dev/null)"
fi
# 2 scenes x 4 methods x 2 quick budgets.
rows=$(tail -n +2 "$csv" 2>/dev/null | grep -c .)
[ "$rows" = 16 ] && pass || fail "expected 16 rows, got $rows"
bad=$(tail -n +2 "$csv" 2>/dev/null | awk -F, '
  function finite(v) { return v ~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/ }
  !(finite($5) && finite($6) && finite($7) && finite($9) && finite($10) && $6 >= 0 && $7 >= 0 && $9 > 0 && $10 > 0) { print }')
[ -z "$bad" ] && pass || fail "non-finite or negative values: $bad"
# mean_z2: a finite non-negative number for pathtrace, nan for the deterministic methods.
bad=$(tail -n +2 "$csv" 2>/dev/null | awk -F, '
  ($2 == "pathtrace") != ($8 ~ /^[0-9.]+(e[-+]?[0-9]+)?$/) { print }')
[ -z "$bad" ] && pass || fail "mean_z2 column: $bad"
# Every method of each scene is present.
for method in straight walter holzschuch pathtrace; do
  [ "$(grep -c ",$method," "$csv")" = 4 ] && pass || fail "$method rows"
done
for name in bumpy-sphere tile; do
  for kind in error images; do
    png="$work/new/study/${name}_$kind.png"
    if [ -s "$png" ] && head -c 8 "$png" | od -An -c | grep -q "P   N   G"; then
      pass
    else
      fail "missing $png"
    fi
  done
done

# From any directory, without scenes: the shipped scenes are found (beside an installed program,
# else in the source tree it was built from).
if (cd "$work" && "$exe" render --study --quick --out elsewhere >"$work/stdout2" 2>"$work/stderr2"); then
  pass
else
  fail "study from $work: $(cat "$work/stderr2")"
fi
for name in bumpy-sphere tile; do
  [ "$(grep -c "^$name," "$work/elsewhere/render_study.csv" 2>/dev/null)" = 8 ] && pass ||
    fail "the default study lacks $name"
done

report cli.render_study
