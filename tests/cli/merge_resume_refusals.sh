#!/usr/bin/env bash
# Usage: merge_resume_refusals.sh SCATTERLAB TAMPER_FILE
# Inputs that look right but are not, made from real outputs with tamper_file:
#   merge refuses a partial input, a NaN or infinite tally, an unknown format_version, batch and
#   photon counts that disagree, a negative mean of a tally that cannot be negative, a seed no
#   run can have; info and fit refuse grid edges that are not finite, do not increase or are
#   one too few, and an unknown format_version, as merge does; merge keeps /models when the
#   inputs agree on them, and says in one line what it leaves out when they do not;
#   --resume refuses a damaged checkpoint: numbers that are not finite, negative Welford squares,
#   counts out of range, another format_version, and any value edited after it was written (its
#   checksum); a damaged global heap, on which HDF5 itself would hang or crash, is refused by info
#   and merge.
# Each refusal: exit 2, one line naming FILE, FILES or --resume and the file, nothing touched.
set -u
exe=$(realpath "$1")
tamper=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

tiny=(--photons 4000 --batches 4 --threads 1 --theta-bins 6 --phi-bins 8 --r-bins 4 --z-bins 4)
"$exe" simulate "${tiny[@]}" --seed 1 --out s1.h5 >/dev/null || fail "setup: s1.h5"
"$exe" simulate "${tiny[@]}" --seed 2 --out s2.h5 >/dev/null || fail "setup: s2.h5"

# damaged NAME FROM CHANGE...: a copy of FROM as NAME with each CHANGE (the arguments of
# tamper_file after the file, separated by "+") made to it.
damaged() {
  local name=$1 from=$2
  shift 2
  cp "$from" "$name" || fail "setup: $name"
  local change=()
  for word in "$@" +; do
    if [ "$word" = + ]; then
      "$tamper" "$name" "${change[@]}" || fail "setup: $name: ${change[*]}"
      change=()
    else
      change+=("$word")
    fi
  done
}

# Merge.
damaged partial.h5 s2.h5 attribute / partial int 1 + attribute / batches_done int 2 \
  + attribute / photons_run int 2000
damaged nan.h5 s2.h5 element tallies/absorbed mean 0 nan
damaged inf.h5 s2.h5 element tallies/absorbed stderr 0 inf
damaged negative.h5 s2.h5 element tallies/absorbed stderr 0 -1
damaged version.h5 s2.h5 attribute / format_version int 2
damaged batches.h5 s2.h5 attribute / batches_done int 3
damaged photons.h5 s2.h5 attribute / photons_run int 3999
expect_refused "merge: partial input" "FILES: partial.h5 is partial" merge s1.h5 partial.h5 -o m.h5
expect_refused "merge: NaN tally" "FILES: nan.h5 .*nan" merge s1.h5 nan.h5 -o m.h5
expect_refused "merge: infinite stderr" "FILES: inf.h5 .*inf" merge inf.h5 s1.h5 -o m.h5
expect_refused "merge: negative stderr" "FILES: negative.h5" merge s1.h5 negative.h5 -o m.h5
expect_refused "merge: unknown format_version" "FILES: version.h5 has format_version 2" \
  merge s1.h5 version.h5 -o m.h5
expect_refused "merge: batches_done against parameters.batches" "FILES: batches.h5 .*batches_done" \
  merge s1.h5 batches.h5 -o m.h5
expect_refused "merge: photons_run against parameters.photons" "FILES: photons.h5 .*photons_run" \
  merge s1.h5 photons.h5 -o m.h5
damaged negative-mean.h5 s2.h5 element tallies/radiance mean 0 -1
damaged seed.h5 s2.h5 attribute parameters seed int -1
expect_refused "merge: negative radiance" "FILES: negative-mean.h5 has -1 in tallies/radiance/mean" \
  merge s1.h5 negative-mean.h5 -o m.h5
expect_refused "merge: seed -1" "FILES: seed.h5 has seed -1" merge s1.h5 seed.h5 -o m.h5

# info and fit: a file that contradicts itself is refused by name, as merge refuses it.
damaged nan-edge.h5 s2.h5 element grid r 2 nan
damaged reversed.h5 s2.h5 element grid z 1 100
damaged short.h5 s2.h5 element grid theta 3 drop
damaged theta-range.h5 s2.h5 element grid theta 6 4
for bad in nan-edge reversed short version; do
  expect_refused "info: $bad" "FILE: $bad.h5 .*\(damaged\|format_version\)" info "$bad.h5"
  expect_refused "fit: $bad" "FILE: $bad.h5 .*\(damaged\|format_version\)" \
    fit "$bad.h5" --models sg
  expect_refused "merge: $bad" "FILES: $bad.h5" merge s1.h5 "$bad.h5" -o m.h5
done
expect_refused "fit: theta past pi" "FILE: theta-range.h5: its direction grid" \
  fit theta-range.h5 --models sg

# The damage is what is refused: the same merge of sound files goes through.
if "$exe" merge s1.h5 s2.h5 -o sound.h5 >/dev/null 2>"$scratch/err" && [ ! -s "$scratch/err" ]
then pass; else fail "merge of sound files: $(cat "$scratch/err")"; fi

# /models: kept when the inputs agree, left out (saying so) when they do not.
half=(searchlight --photons 4000 --batches 4 --threads 1 --r-bins 8)
"$exe" "${half[@]}" --seed 1 --out h1.h5 >/dev/null || fail "setup: h1.h5"
"$exe" "${half[@]}" --seed 2 --out h2.h5 >/dev/null || fail "setup: h2.h5"
models() { "$exe" info "$1" | sed -n '/^models/,$p'; }
if "$exe" merge h1.h5 h2.h5 -o hm.h5 >/dev/null 2>"$scratch/err" && [ ! -s "$scratch/err" ] &&
  [ -n "$(models h1.h5)" ] && [ "$(models hm.h5)" = "$(models h1.h5)" ]; then pass; else
  fail "models kept: $(cat "$scratch/err"; models hm.h5)"; fi
# The first model that has curves, and its first curve ("model   curve, curve, ...").
read -r model curve < <(models h2.h5 |
  awk 'NR > 1 && NF > 1 {sub(",", "", $2); print $1, $2; exit}')
damaged h2-model.h5 h2.h5 element "models/$model" "$curve" 0 0.125
if "$exe" merge h1.h5 h2-model.h5 -o hx.h5 >/dev/null 2>"$scratch/err" &&
  [ "$(grep -c . "$scratch/err")" -eq 1 ] && grep -q "left out /models.*$model" "$scratch/err" &&
  [ -z "$(models hx.h5)" ]; then pass; else
  fail "models that differ ($model $curve): $(cat "$scratch/err"; models hx.h5)"; fi

# --resume. A real checkpoint: a run of 4 long batches stopped after the first one was saved.
run=(simulate --photons 2000000 --batches 4 --threads 1 --seed 5 --theta-bins 6 --phi-bins 8)
"$exe" "${run[@]}" --out c.h5 --checkpoint-interval 1b >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1500); do [ -e c.h5.checkpoint ] && break; sleep 0.02; done
kill -INT $pid
wait $pid
[ -e c.h5.checkpoint ] || fail "setup: no checkpoint"
damaged nan.ckpt c.h5.checkpoint element / welford_mean 3 nan
damaged inf.ckpt c.h5.checkpoint element / welford_squares 3 inf
damaged negative.ckpt c.h5.checkpoint element / welford_squares 3 -1
damaged many.ckpt c.h5.checkpoint attribute / batches_folded int 9
damaged none.ckpt c.h5.checkpoint attribute / batches_folded int 0
damaged events.ckpt c.h5.checkpoint attribute / scattering_events int -5
damaged version.ckpt c.h5.checkpoint attribute / format_version int 3
damaged old.ckpt c.h5.checkpoint attribute / format_version int 1
damaged walltime.ckpt c.h5.checkpoint attribute / wall_seconds double 0.5
damaged edited.ckpt c.h5.checkpoint element / welford_mean 3 0.125
for bad in nan inf negative many none events version old walltime edited; do
  expect_refused "resume: $bad" "--resume.*$bad.ckpt" \
    "${run[@]}" --out c.h5 --checkpoint "$bad.ckpt" --resume
done

# Files on which HDF5 1.10.8 itself hangs or crashes (tests/fuzz/libhdf5): a damaged global heap
# is refused before HDF5 reads it, by every command that reads a file.
for bad in global-heap-loop global-heap-read-past-end global-heap-wild-walk; do
  cp "$(dirname "$0")/../fuzz/libhdf5/$bad.h5" "$bad.h5" || fail "setup: $bad.h5"
  expect_refused "info: $bad" "FILE: .*global heap" info "$bad.h5"
  expect_refused "merge: $bad" "FILES: .*global heap" merge s1.h5 "$bad.h5" -o m.h5
done
# A damaged group of many links, on which HDF5 frees a pointer it never set when it lists them
# in an order the file does not index; fresh memory filled with a pattern (MALLOC_PERTURB_) makes
# that a crash every time.
cp "$(dirname "$0")/../fuzz/libhdf5/dense-link-free.h5" . || fail "setup: dense-link-free.h5"
for perturb in 85 165; do
  ENV_SET="MALLOC_PERTURB_=$perturb" expect_refused "info: dense-link-free ($perturb)" "FILE: " \
    info dense-link-free.h5
  ENV_SET="MALLOC_PERTURB_=$perturb" expect_refused "merge: dense-link-free ($perturb)" \
    "FILES: " merge s1.h5 dense-link-free.h5 -o m.h5
done

report "merge and resume refusals"
