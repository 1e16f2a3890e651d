#!/usr/bin/env bash
# Usage: long_runs.sh SCATTERLAB SAME_TALLIES
# A run killed with SIGKILL resumes with --resume to the same bits as an uninterrupted run; SIGINT
# writes a file marked partial and exits 130; merge and sweeps from the command line.
set -u
exe=$(realpath "$1")
same=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

# Long enough to be stopped mid-run (about a second on 2 threads), short enough for CI.
run=(simulate --photons 6000000 --batches 48 --threads 2 --seed 11 --theta-bins 6 --phi-bins 8)
"$exe" "${run[@]}" --out full.h5 >/dev/null || fail "uninterrupted run"

# wait_for FILE: until it exists (at most ~20 s).
wait_for() { for _ in $(seq 1000); do [ -e "$1" ] && return 0; sleep 0.02; done; return 1; }

# SIGKILL after the first checkpoint, then --resume.
"$exe" "${run[@]}" --out killed.h5 --checkpoint-interval 4b >/dev/null 2>&1 &
pid=$!
if wait_for killed.h5.checkpoint; then
  kill -KILL $pid 2>/dev/null
  wait $pid 2>/dev/null
  if [ -e killed.h5 ]; then
    fail "kill: the run finished before it was killed (machine too fast for this test?)"
  elif "$exe" "${run[@]}" --out killed.h5 --resume >resume.out 2>&1 &&
    grep -q "resuming after batch" resume.out && "$same" full.h5 killed.h5 >/dev/null; then
    pass
  else
    fail "kill and resume: $(cat resume.out; "$same" full.h5 killed.h5)"
  fi
  [ ! -e killed.h5.checkpoint ] && ! compgen -G "killed.h5.checkpoint.tmp-*" >/dev/null && pass ||
    fail "checkpoint or its temporaries left after the run completed: $(ls)"
else
  fail "no checkpoint written"
  kill -KILL $pid 2>/dev/null
fi

# SIGINT: drops the round it cuts short, writes a partial file of the whole batches before it, says
# so, exits 130; --resume completes it.
"$exe" "${run[@]}" --out stopped.h5 --checkpoint-interval 4b >/dev/null 2>stopped.err &
pid=$!
wait_for stopped.h5.checkpoint
kill -INT $pid
wait $pid
status=$?
if [ $status -eq 130 ] && grep -q "interrupted after" stopped.err &&
  "$exe" info stopped.h5 | grep -q "PARTIAL"; then pass; else
  fail "SIGINT: exit $status, $(cat stopped.err)"
fi
if "$exe" "${run[@]}" --out stopped.h5 --resume >/dev/null 2>&1 && "$same" full.h5 stopped.h5 >/dev/null &&
  ! "$exe" info stopped.h5 | grep -q PARTIAL; then pass; else fail "resume after SIGINT"; fi

# A checkpoint of another run is refused, naming --resume.
"$exe" "${run[@]}" --out other.h5 --checkpoint other.ckpt --checkpoint-interval 4b >/dev/null 2>&1 &
pid=$!
wait_for other.ckpt
kill -INT $pid
wait $pid
if ! "$exe" "${run[@]}" --seed 12 --out other.h5 --checkpoint other.ckpt --resume 2>err.txt >/dev/null &&
  grep -q -- "--resume" err.txt; then pass; else fail "foreign checkpoint: $(cat err.txt)"; fi
if ! "$exe" "${run[@]}" --out x.h5 --checkpoint-interval 5q 2>err.txt >/dev/null &&
  grep -q -- "--checkpoint-interval" err.txt; then pass; else fail "bad interval: $(cat err.txt)"; fi

# Merge: two seeds pool; the same seed twice or another albedo is refused.
small=(simulate --photons 20000 --batches 4 --theta-bins 6 --phi-bins 8)
"$exe" "${small[@]}" --seed 1 --out s1.h5 >/dev/null && "$exe" "${small[@]}" --seed 2 --out s2.h5 >/dev/null &&
  "$exe" "${small[@]}" --seed 3 --albedo 0.7 --out s3.h5 >/dev/null
if "$exe" merge s1.h5 s2.h5 -o merged.h5 >/dev/null && "$exe" info merged.h5 | grep -q "merged from"
then pass; else fail "merge"; fi
if ! "$exe" merge s1.h5 s1.h5 -o dup.h5 2>err.txt && grep -q parameters.seed err.txt && [ ! -e dup.h5 ]
then pass; else fail "duplicate seed: $(cat err.txt)"; fi
if ! "$exe" merge s1.h5 s3.h5 -o bad.h5 2>err.txt && grep -q parameters.albedo err.txt && [ ! -e bad.h5 ]
then pass; else fail "mismatched albedo: $(cat err.txt)"; fi

# Sweep: every combination once; a second run skips them all.
printf '[medium]\nalbedo = [0.5, 0.9]\ng = [0, 0.9]\n[run]\nphotons = 4000\nbatches = 4\n' >sweep.toml
if "$exe" simulate --scene sweep.toml --out sweep --theta-bins 6 --phi-bins 8 >/dev/null &&
  [ "$(ls sweep | wc -l)" -eq 4 ] && [ -f "sweep/albedo=0.9_g=0.h5" ]; then pass; else
  fail "sweep: $(ls sweep)"; fi
if [ "$("$exe" simulate --scene sweep.toml --out-dir sweep --theta-bins 6 --phi-bins 8 | grep -c '^skip')" -eq 4 ]
then pass; else fail "sweep did not skip what was done"; fi
if ! "$exe" simulate --scene sweep.toml 2>err.txt >/dev/null && grep -q -- --out err.txt; then pass; else
  fail "sweep without --out: $(cat err.txt)"; fi

report "long runs"
