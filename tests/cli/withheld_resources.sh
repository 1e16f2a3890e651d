#!/usr/bin/env bash
# Usage: withheld_resources.sh SCATTERLAB SOURCE_DIR
# Every transport command runs with whatever threads OpenMP grants: under OMP_DYNAMIC=true with
# the default --threads 0, and under OMP_THREAD_LIMIT=1 with --threads 2, where it says that it
# got 1 of the 2 threads. And a run whose tallies need more than ulimit -v leaves is refused
# before any work, naming the limit, with nothing written.
set -u
exe=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/harness.sh"
scenes=$source_dir/data/scenes
few=(--photons 2000 --batches 4)

# run_granted NAME ENV -- COMMAND...: exit 0 under the environment variable ENV.
run_granted() {
  local name=$1 environment=$2
  shift 3
  timeout -k 10 300 env "$environment" "$exe" "$@" >"$scratch/stdout" 2>"$scratch/stderr"
  local status=$?
  if [ $status -ne 0 ]; then
    fail "$name: exit $status: $(tail -3 "$scratch/stderr")"
  else
    pass
  fi
}

# Each run works in a directory of its own, where OUT names its file (a directory for validate)
# and mcml writes its files.
commands=(
  "simulate infinite|simulate ${few[*]} --out OUT.h5"
  "simulate point source|simulate --scene $scenes/point-source.toml ${few[*]} --out OUT.h5"
  "simulate sphere|simulate --scene $scenes/lit-sphere.toml ${few[*]} --out OUT.h5"
  "simulate mesh|simulate --scene $scenes/lit-mesh.toml ${few[*]} --out OUT.h5"
  "simulate slab|simulate --scene $scenes/skin-slab.toml ${few[*]} --out OUT.h5"
  "searchlight|searchlight --scene $scenes/searchlight.toml ${few[*]} --out OUT.h5"
  "mcml|mcml $source_dir/data/mcml/sample.mci ${few[*]}"
  "validate searchlight|validate searchlight --quick --out OUT"
)
run=0
for entry in "${commands[@]}"; do
  name=${entry%%|*}
  for environment in OMP_DYNAMIC=true OMP_THREAD_LIMIT=1; do
    run=$((run + 1))
    mkdir "run$run"
    read -r -a words <<<"${entry#*|}"
    words=("${words[@]/OUT/out}")
    threads=()
    [ "$environment" = OMP_THREAD_LIMIT=1 ] && threads=(--threads 2)
    cd "run$run" || exit 1
    run_granted "$name, $environment" "$environment" -- "${words[@]}" "${threads[@]}"
    cd .. || exit 1
    # The run's summary says how many threads it got.
    if [ "$environment" = OMP_THREAD_LIMIT=1 ] && [ "${words[0]}" != validate ] &&
      ! grep -q "OpenMP granted 1 of the 2 threads" "$scratch/stdout"; then
      fail "$name: does not say that OpenMP granted 1 of 2 threads: $(cat "$scratch/stdout")"
    fi
  done
done

# A run of 4.7 GiB of tallies (radiance on 400 x 400 x 18 x 36 cells, 6 arrays) under a
# ulimit -v of half that: refused before any work, with the limit named.
big=(--r-bins 400 --z-bins 400 --photons 2000 --batches 4 --threads 1 --out big.h5)
estimate=$("$exe" simulate "${big[@]}" --memory-limit 1K 2>&1 | grep -o '[0-9.]* GiB for' | head -1)
[ -n "$estimate" ] || fail "setup: no estimate in GiB in the refusal under --memory-limit 1K"
half_kib=$(awk -v g="${estimate%% *}" 'BEGIN { printf "%d", g * 1024 * 1024 / 2 }')
snapshot >"$scratch/before"
(ulimit -v "$half_kib" && timeout -k 10 60 "$exe" simulate "${big[@]}") >"$scratch/stdout" \
  2>"$scratch/stderr"
status=$?
snapshot >"$scratch/after"
if [ $status -ne 2 ]; then
  fail "ulimit -v $half_kib KiB: exit $status, expected 2: $(cat "$scratch/stderr")"
elif ! grep -q "ulimit -v" "$scratch/stderr"; then
  fail "ulimit -v: the refusal does not name the limit: $(cat "$scratch/stderr")"
elif [ -s "$scratch/stdout" ] && grep -q photons "$scratch/stdout"; then
  fail "ulimit -v: work started before the refusal: $(cat "$scratch/stdout")"
elif ! cmp -s "$scratch/before" "$scratch/after"; then
  fail "ulimit -v: files changed: $(diff "$scratch/before" "$scratch/after")"
else
  pass
fi

report withheld_resources
