#!/usr/bin/env bash
# Sets up, builds the fuzz targets (tests/fuzz) with clang's libFuzzer under AddressSanitizer and
# UndefinedBehaviorSanitizer in build-fuzz, and runs each on its seed corpus for SECONDS_PER_TARGET
# (60 by default), one after the other. Prints each target's executions, executions per second
# and coverage; fails on any finding (crash, sanitizer report, uncaught exception, timeout, out of
# memory, leak), whose input is kept in build-fuzz/findings.
# FUZZ_BUILD_TYPE (Release by default) is the build's CMAKE_BUILD_TYPE.
# FUZZ_SEED=N fixes libFuzzer's random seed (CI's short runs use one, so that they explore the same
# inputs each time); unset, each run draws its own.
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
if ! [[ $seconds =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: scripts/fuzz.sh [SECONDS_PER_TARGET] (a whole number of seconds, 60 by default)" >&2
  exit 2
fi

scripts/setup.sh
# FUZZ_BUILD_TYPE=Debug builds unoptimised (-O0, line tables), in about a third of the time,
# which suits CI's short runs; long runs want Release's speed.
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE="${FUZZ_BUILD_TYPE:-Release}" \
  -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DCMAKE_C_FLAGS_DEBUG=-g1 -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DSCATTERLAB_FUZZ=ON -DSCATTERLAB_BUILD_TESTS=OFF \
  -DSCATTERLAB_BUILD_BENCH=OFF -DSCATTERLAB_BUILD_PYTHON=OFF >/dev/null
cmake --build build-fuzz --target scatterlab_fuzzers -j "$(nproc)"

root=$PWD
findings=$root/build-fuzz/findings
mkdir -p "$findings"
# New inputs go to a scratch corpus, never into the repository's; each target's temporary files
# (tests/fuzz/fuzz_support.hpp) go under it too, and all of it is removed at the end.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Each target's seeds: its folder of tests/fuzz/corpus, and the shipped files of its kind.
declare -A shipped=([scene]=data/scenes [mcml_input]=data/mcml [text_model]=data/models)
# The per-input time limit: the targets leave out the sizes that only run longer (a mesh of
# millions of triangles; tests/fuzz/README.md), and the rest ends in seconds under the sanitizers.
timeout_s=60
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}

failed=()
printf '%-16s %12s %8s %7s %7s  %s\n' target executions exec/s cov ft result
for target in scene mcml_input obj_mesh hdf5_file explore_request text_model; do
  corpus=$scratch/corpus-$target
  mkdir -p "$corpus" "$scratch/tmp-$target"
  seeds=("$root/tests/fuzz/corpus/$target")
  [ -n "${shipped[$target]:-}" ] && seeds+=("$root/${shipped[$target]}")
  options=(-max_total_time="$seconds" -timeout="$timeout_s" -rss_limit_mb=2048
           -print_final_stats=1 -artifact_prefix="$findings/$target-")
  [ -n "${FUZZ_SEED:-}" ] && options+=(-seed="$FUZZ_SEED")
  [ -f "tests/fuzz/$target.dict" ] && options+=(-dict="$root/tests/fuzz/$target.dict")
  log=$findings/$target.log
  status=0
  TMPDIR=$scratch/tmp-$target "build-fuzz/tests/fuzz/fuzz_$target" "${options[@]}" "$corpus" \
    "${seeds[@]}" >"$log" 2>&1 || status=$?
  # libFuzzer's last status line ("#N ... cov: C ft: F ... exec/s: E ...") and its final stats.
  last=$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
  runs=$(sed -nE 's/^stat::number_of_executed_units: ([0-9]+).*/\1/p' "$log" | tail -n 1)
  rate=$(sed -nE 's/^stat::average_exec_per_sec: +([0-9]+).*/\1/p' "$log" | tail -n 1)
  result=ok
  if [ "$status" -ne 0 ]; then
    result="FAILED (status $status; $log)"
    failed+=("$target")
  fi
  printf '%-16s %12s %8s %7s %7s  %s\n' "$target" "${runs:-?}" "${rate:-?}" "${cov:-?}" \
    "${ft:-?}" "$result"
done

if ((${#failed[@]})); then
  for target in "${failed[@]}"; do
    echo "--- $target: the end of $findings/$target.log"
    tail -n 40 "$findings/$target.log"
  done
  echo "fuzz: findings in ${failed[*]}; their inputs are $findings/<target>-*" >&2
  exit 1
fi
echo "fuzz: no findings in ${seconds} s per target"
