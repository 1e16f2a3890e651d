#!/usr/bin/env bash
# Usage: materials.sh SCATTERLAB SOURCE_DIR
# scatterlab materials lists every material of every table in data/materials, and with a name
# (found however its words are joined, as a scene finds it) prints that material's coefficients
# as the table gives them; an unknown name is refused with the nearest.
set -u
exe=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

"$exe" materials >list.txt || fail "materials"
for table in "$src"/data/materials/*.toml; do
  id=$(basename "$table" .toml)
  grep -q "^$id: " list.txt || fail "materials: table $id not listed"
  for name in $(sed -n 's/^\[materials\.\([a-z0-9_]*\)\].*/\1/p' "$table"); do
    grep -qw -- "$name" list.txt || fail "materials: $id/$name not listed"
  done
done
pass

# Jensen 2001's skim milk: sigma_a 0.0014 0.0025 0.0142 and sigma_s' 0.70 1.22 1.90 per mm.
"$exe" materials "Skim Milk" >milk.txt || fail "materials \"Skim Milk\""
if grep -q "^jensen2001/skimmilk: " milk.txt &&
  grep -Eq "^  sigma_a \[1/mm\] +0\.0014 +0\.0025 +0\.0142$" milk.txt &&
  grep -Eq "^  sigma_s' \[1/mm\] +0\.7 +1\.22 +1\.9$" milk.txt; then
  pass
else
  fail "materials \"Skim Milk\": $(cat milk.txt)"
fi

expect_refused "an unknown material" "NAME: .*did you mean \"wholemilk\"" materials "whole milkk"

report "materials"
