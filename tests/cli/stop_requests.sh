#!/usr/bin/env bash
# Usage: stop_requests.sh SCATTERLAB SAME_TALLIES [MPIEXEC]
# A stop request is honoured within 2 s even when one batch would take many minutes: the
# unfinished batches are dropped, nothing partial is written when no batch was whole, and a run
# stopped in mid-batch (on one process, or on two ranks that see the signal at different times)
# resumes to the same bits as an uninterrupted run.
set -u
exe=$(realpath "$1")
same=$(realpath "$2")
mpiexec=${3:-}
source "$(dirname "$0")/harness.sh"

# wait_for FILE: until it exists (at most ~30 s).
wait_for() { for _ in $(seq 1500); do [ -e "$1" ] && return 0; sleep 0.02; done; return 1; }

# stop_within NAME SIGNAL PID: sends SIGNAL to PID and checks it exits with 130 within 2 s
# (killed after 10 s, so that a run that does not stop fails the test rather than hanging it).
stop_within() {
  local name=$1 signal=$2 pid=$3
  local start=$EPOCHREALTIME
  kill "-$signal" "$pid"
  for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$pid" 2>/dev/null && echo "$name: still running 10 s after SIG$signal: killed"
  wait "$pid"
  local status=$? elapsed
  elapsed=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }')
  echo "$name: exit $status, $elapsed s after SIG$signal"
  if [ $status -ne 130 ]; then
    fail "$name: exit $status, not 130"
  elif awk -v t="$elapsed" 'BEGIN { exit !(t > 2) }'; then
    fail "$name: took $elapsed s to stop"
  else
    pass
  fi
}

# Two batches of 5e9 photons on two threads: hours. Stopped in them, nothing is whole: no file, no
# checkpoint, and the message says so.
"$exe" simulate --photons 1e10 --batches 2 --threads 2 --seed 3 --theta-bins 6 --phi-bins 8 \
  --out long.h5 --checkpoint-interval 1b >/dev/null 2>long.err &
pid=$!
sleep 2  # the signal handlers are in place well before
stop_within "first batches" INT $pid
if grep -q "interrupted before the first batch" long.err && [ "$(error_lines long.err)" -eq 1 ] &&
  [ -z "$(ls -A | grep long.h5)" ]; then pass; else
  fail "first batches: $(cat long.err; ls)"; fi

# Stopped once the first checkpoint is saved: keeps the batches that are whole (two, or three when
# one thread took batch 2 while the other was still in batch 1, as happens on a loaded machine),
# and --resume ends as an uninterrupted run.
run=(simulate --photons 24000000 --batches 4 --threads 2 --seed 4 --theta-bins 6 --phi-bins 8)
"$exe" "${run[@]}" --out full.h5 >/dev/null || fail "uninterrupted run"
"$exe" "${run[@]}" --out part.h5 --checkpoint-interval 2b >/dev/null 2>part.err &
pid=$!
wait_for part.h5.checkpoint || fail "no checkpoint after the first two batches"
stop_within "after the first checkpoint" TERM $pid
if grep -Eq "interrupted after [23] of 4 batches" part.err && "$exe" info part.h5 | grep -q PARTIAL &&
  "$exe" "${run[@]}" --out part.h5 --resume >/dev/null 2>&1 && "$same" full.h5 part.h5 >/dev/null
then pass; else fail "resume after a stop in mid-batch: $(cat part.err)"; fi

# Two ranks: mpirun forwards SIGUSR1; every rank drops the same group of batches (one per rank).
if [ -n "$mpiexec" ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1
  "$mpiexec" --oversubscribe -n 2 "$exe" "${run[@]}" --threads 1 --out ranks.h5 \
    --checkpoint-interval 1b >/dev/null 2>ranks.err &
  pid=$!
  wait_for ranks.h5.checkpoint || fail "no checkpoint on two ranks"
  kill -USR1 $pid
  wait $pid
  if grep -q "interrupted after 2 of 4 batches" ranks.err &&
    "$exe" "${run[@]}" --out ranks.h5 --resume >/dev/null 2>&1 &&
    "$same" full.h5 ranks.h5 >/dev/null
  then pass; else fail "two ranks stopped in mid-batch: $(cat ranks.err)"; fi
fi

report "stop requests"
