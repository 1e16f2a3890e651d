#!/usr/bin/env bash
# Usage: printed_totals.sh SCATTERLAB SOURCE_DIR
# A total printed by two commands for the same run is the same figure in both: the once-scattered
# reflectance of `searchlight` and of `validate searchlight` (same photons, seed and batches), and
# every scalar of a `searchlight` or `simulate` summary and of `info` on the file it wrote.
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

# "MEAN ± STDERR" after PREFIX on the line of FILE that holds it.
estimate_after() { grep -o -- "$2[0-9.e+-]* ± [0-9.e+-]*" "$1" | head -1 | sed "s/^$2//"; }

# validate searchlight --quick: albedo 0.99, g 0, eta 1.3, 1e5 photons, 100 rings, 20 depths.
"$exe" validate searchlight --quick --seed 1 --threads 2 --out validation >validate.out 2>&1 ||
  fail "validate searchlight: $(cat validate.out)"
"$exe" searchlight --albedo 0.99 --g 0 --eta 1.3 --photons 1e5 --r-bins 100 --z-bins 20 \
  --seed 1 --threads 2 --out half.h5 >searchlight.out 2>&1 ||
  fail "searchlight: $(cat searchlight.out)"
"$exe" info half.h5 >half.info 2>&1 || fail "info half.h5: $(cat half.info)"

single_validate=$(estimate_after validate.out "once scattered: exact total [0-9.]*, Monte Carlo ")
single_searchlight=$(estimate_after searchlight.out "diffuse reflectance: ")
single_info=$(grep -A2 "^  diffuse_reflectance_single " half.info | tail -1 | sed 's/^ *//')
if [ -n "$single_validate" ] && [ "$single_validate" = "$single_searchlight" ] &&
  [ "$single_searchlight" = "$single_info" ]; then pass; else
  fail "once-scattered total: validate '$single_validate', searchlight '$single_searchlight'," \
    "info '$single_info'"
fi

# Every scalar of the summaries, as info prints it from the file.
"$exe" simulate --albedo 0.9 --g 0.5 --photons 20000 --batches 8 --seed 3 --threads 2 \
  --out beam.h5 >simulate.out 2>&1 || fail "simulate: $(cat simulate.out)"
"$exe" info beam.h5 >beam.info 2>&1 || fail "info beam.h5: $(cat beam.info)"
for case in "searchlight.out half.info specular_reflectance" \
  "searchlight.out half.info diffuse_reflectance" "searchlight.out half.info absorbed" \
  "simulate.out beam.info absorbed" "simulate.out beam.info absorbed_outside_grid"; do
  set -- $case
  summary=$(estimate_after "$1" " $3 ")
  info=$(grep -A2 "^  $3 " "$2" | tail -1 | sed 's/^ *//')
  if [ -n "$summary" ] && [ "$summary" = "$info" ]; then pass; else
    fail "$3: summary '$summary', info '$info'"
  fi
done

report "printed totals"
