#!/usr/bin/env bash
# Usage: validate_litsphere.sh SCATTERLAB SOURCE_DIR
# validate litsphere --quick from the command line: the error table names every case and model,
# the two CSV files hold every psi bin of every case with no NaN, there is one PNG per case; and
# bad flags get one error naming the flag, exit status 2, and no output directory.
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

cases=9 bins=36 models=4  # three diffusion models and the measured profile
if "$exe" validate litsphere --quick --threads 2 --out "$work/ls" >"$work/stdout" \
  2>"$work/stderr"; then
  pass
  rows=$(grep -cE " (dipole|better_dipole|quantized_diffusion|measured) " "$work/stdout")
  if [ "$rows" -eq $((cases * models)) ]; then pass; else
    fail "error table: $rows rows of $((cases * models)): $(cat "$work/stdout")"; fi
  lines=$(wc -l <"$work/ls/litsphere_exitance.csv")
  if [ "$lines" -eq $((1 + cases * bins)) ]; then pass; else
    fail "litsphere_exitance.csv: $lines lines"; fi
  lines=$(wc -l <"$work/ls/litsphere_errors.csv")
  if [ "$lines" -eq $((1 + cases * models)) ]; then pass; else
    fail "litsphere_errors.csv: $lines lines"; fi
  if grep -qi "nan" "$work/ls/litsphere_exitance.csv"; then
    fail "litsphere_exitance.csv holds NaN"; else pass; fi
  pngs=0
  for png in "$work"/ls/litsphere_*.png; do
    if [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; then
      pngs=$((pngs + 1))
    fi
  done
  if [ "$pngs" -eq "$cases" ]; then pass; else fail "$pngs PNG files of $cases"; fi
else
  fail "validate litsphere --quick: $(cat "$work/stderr")"
fi

refused() {  # NAME FLAG ARGS...: exit status 2, one line naming FLAG, no output directory
  local name=$1 flag=$2
  shift 2
  "$exe" validate litsphere "$@" --out "$work/$name" >/dev/null 2>"$work/stderr"
  local status=$?
  if [ "$status" -eq 2 ] && [ "$(wc -l <"$work/stderr")" -eq 1 ] &&
    grep -q -- "$flag" "$work/stderr" && [ ! -e "$work/$name" ]; then
    pass
  else
    fail "$name: status $status, $(cat "$work/stderr")"
  fi
}
refused samples --samples --samples 1
refused quick_photons --photons --quick --photons 1e5
refused seed --seed --seed 9223372036854775800
refused threads --threads --threads -1

report validate_litsphere
