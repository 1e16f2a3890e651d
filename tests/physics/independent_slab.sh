#!/usr/bin/env bash
# Usage: independent_slab.sh SCATTERLAB SOURCE_DIR
# The layered slab against an independent Monte Carlo (tests/tools/independent_slab.py, numpy,
# written from the physics rather than from scatterlab's code), on MCML's sample and on a stack
# with every kind of interface: a clear first layer (MCML's glass), mismatched inner interfaces,
# a backward-scattering layer and another index below. R_d, T_t and A agree within 4 combined
# standard errors (fixed seeds; scatterlab with implicit capture, the other analog).
set -u
exe=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0

cat >mixed.toml <<'TOML'
[geometry]
type = "slab"
n_above = 1.0
n_below = 1.2
[[layers]]
mu_a = 0
mu_s = 0
g = 0
n = 1.52
thickness = 0.05
[[layers]]
mu_a = 2
mu_s = 50
g = 0.8
n = 1.4
thickness = 0.05
[[layers]]
mu_a = 0.5
mu_s = 20
g = -0.3
n = 1.33
thickness = 0.1
[run]
weighting = "implicit"
TOML

compare() {
  local name=$1 file=$2
  /usr/bin/python3 "$source_dir/tests/tools/independent_slab.py" "$file" 2e6 7 >independent.txt || {
    echo "FAIL: $name: the independent Monte Carlo failed"
    failures=$((failures + 1))
    return
  }
  "$exe" info "$file" >info.txt
  while read -r tally value error; do
    # The tally's line in info: "      0.237906 ± 0.00033" after its name's line.
    local ours ours_error
    read -r ours ours_error < <(grep -A2 "^  $tally  " info.txt | grep "±" | head -1 |
      awk '{print $1, $3}')
    if /usr/bin/python3 -c "import sys; a, sa, b, sb = map(float, sys.argv[1:]); \
sys.exit(0 if abs(a - b) <= 4 * (sa * sa + sb * sb) ** 0.5 else 1)" \
      "$ours" "$ours_error" "$value" "$error"; then
      echo "$name $tally: scatterlab $ours ± $ours_error, independent $value ± $error"
    else
      echo "FAIL: $name $tally: scatterlab $ours ± $ours_error, independent $value ± $error"
      failures=$((failures + 1))
    fi
  done <independent.txt
}

"$exe" mcml "$source_dir/data/mcml/sample.mci" --photons 2e6 --weighting implicit --seed 3 \
  >/dev/null || { echo "FAIL: mcml sample.mci"; exit 1; }
compare sample sample.h5
"$exe" simulate mixed.toml --photons 2e6 --seed 3 --out mixed.h5 >/dev/null ||
  { echo "FAIL: simulate mixed.toml"; exit 1; }
compare mixed mixed.h5

echo "independent_slab: $failures failed"
[ $failures -eq 0 ]
