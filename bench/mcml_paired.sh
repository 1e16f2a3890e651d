#!/usr/bin/env bash
# MCML 1.2.2 against scatterlab, paired, on MCML's cases a (albedo 0.99, g 0) and b (albedo 0.9,
# g 0.75): an index-matched semi-infinite medium under a normal pencil beam, 1 / cm = 1 / mfp, on
# one thread. MCML runs the case as an .mci (a 10^8 cm layer, n = 1 all round; dr = dz = 0.1 cm,
# 100 x 100 bins); scatterlab runs `searchlight --eta 1` on the same grid with its fluence phi(r, z)
# (scored at every collision, as MCML scores A(r, z)). The two alternate REPS times on the same
# photon count, so that the machine's drift falls on both; the script prints every pair's seconds
# and, per case, the median of the ratios MCML / scatterlab.
#
# Then the layered slab: MCML's own sample and the three-layer skin model of
# data/mcml, each run by MCML and by `scatterlab mcml --threads 1`, analog (scatterlab's default)
# and with MCML's implicit capture (`--weighting implicit`, as MCML weights its photons), PHOTONS
# photons each.
#
#   bench/mcml_paired.sh MCML SCATTERLAB [PHOTONS] [REPS]
#
# MCML is not part of scatterlab: build it from its sources (Wang, Jacques & Zheng 1995).
set -euo pipefail
mcml=$(realpath "$1") scatterlab=$(realpath "$2") photons=${3:-200000} reps=${4:-5}
data=$(realpath "$(dirname "$0")/../data/mcml")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

seconds() {  # seconds COMMAND...: wall time of one run, its output discarded
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1 </dev/null
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN {print b - a}'
}

# paired NAME "MCML COMMAND" "SCATTERLAB COMMAND": REPS alternate runs, each pair's seconds, the
# median ratio. Each run's files are removed before the next.
paired() {
  local name=$1 ratios=() a b ratio median
  for ((i = 0; i < reps; i++)); do
    a=$(seconds $2)
    b=$(OMP_NUM_THREADS=1 seconds $3)
    rm -f ./*.h5 ./*.mco
    ratio=$(awk -v a="$a" -v b="$b" 'BEGIN {print a / b}')
    ratios+=("$ratio")
    printf '%s: MCML %.3f s, scatterlab %.3f s, %.2fx\n' "$name" "$a" "$b" "$ratio"
  done
  median=$(printf '%s\n' "${ratios[@]}" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}')
  printf '%s: median MCML / scatterlab over %d pairs: %.2fx\n' "$name" "$reps" "$median"
}

for case in "a 0.01 0.99 0" "b 0.1 0.9 0.75"; do
  read -r name mua mus g <<<"$case"
  cat >"case_$name.mci" <<EOF
1.0
1
case_$name.mco A
$photons
0.1 0.1
100 100 1
1
1.0
1.0 $mua $mus $g 1e8
1.0
EOF
  albedo=$(awk -v a="$mua" -v s="$mus" 'BEGIN {printf "%.17g", s / (a + s)}')
  # One thread for the models' integrals too (OpenMP's count), as for the transport.
  paired "case $name" "$mcml case_$name.mci" \
    "$scatterlab searchlight --eta 1 --albedo $albedo --g $g --photons $photons --threads 1
     --r-max 10 --r-bins 100 --z-max 10 --z-bins 100 --log-interval 0 --out case_$name.h5"
done

# The slab: the .mci with its photon count replaced (the line after the output file's).
for name in sample skin; do
  awk -v n="$photons" '/^[^#]*\.mco/ {print; getline; print n; next} {print}' \
    "$data/$name.mci" >"$name.mci"
  for weighting in analog implicit; do
    paired "$name, $photons photons, $weighting" "$mcml $name.mci" \
      "$scatterlab mcml $name.mci --threads 1 --weighting $weighting --log-interval 0"
  done
done
