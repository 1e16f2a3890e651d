#!/usr/bin/env bash
# Usage: mpi_runs.sh SCATTERLAB SAME_TALLIES MPIEXEC
# With the same seed, the tallies are bitwise the same for 1 rank x 1 thread, 1 x 2 and 2 x 1;
# a run interrupted on one rank resumes on two; only rank 0 writes and prints.
set -u
exe=$(realpath "$1")
same=$(realpath "$2")
mpiexec=$3
source "$(dirname "$0")/harness.sh"

# Containers run tests as root, on loopback, with no shared-memory single-copy support.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1
mpi() { "$mpiexec" --oversubscribe -n "$@"; }

run=(simulate --photons 400000 --batches 24 --seed 21 --theta-bins 6 --phi-bins 8 --split-orders)
"$exe" "${run[@]}" --threads 1 --out 1x1.h5 >/dev/null || fail "1 x 1"
"$exe" "${run[@]}" --threads 2 --out 1x2.h5 >/dev/null || fail "1 x 2"
if mpi 2 "$exe" "${run[@]}" --threads 1 --out 2x1.h5 >2x1.out 2>2x1.err; then pass; else
  fail "2 x 1: $(cat 2x1.out 2x1.err)"; fi
if "$same" 1x1.h5 1x2.h5 2x1.h5; then pass; else fail "tallies differ between ranks x threads"; fi
# Once: the summary and the progress come from rank 0 alone, and the file says how many ranks
# ran it.
if [ "$(grep -c '^scatterlab simulate' 2x1.out)" -eq 1 ] && [ "$(error_lines 2x1.err)" -eq 0 ] &&
  [ "$(grep -c '^simulate: 0/24 batches, started' 2x1.err)" -eq 1 ] &&
  "$exe" info 2x1.h5 | grep -q "ranks       2"; then pass; else fail "rank 0 only: $(cat 2x1.out 2x1.err)"; fi
# The comparison can fail: another seed differs.
"$exe" "${run[@]}" --seed 22 --threads 1 --out seed22.h5 >/dev/null
if ! "$same" 1x1.h5 seed22.h5 >/dev/null; then pass; else fail "another seed gave the same tallies"; fi

# The searchlight on the same runner: 1 x 1 and 2 x 1 give the same bits.
half=(searchlight --eta 1.33 --albedo 0.9 --g 0.5 --photons 100000 --batches 16 --seed 5 --r-bins 40)
"$exe" "${half[@]}" --threads 1 --out half1.h5 >/dev/null || fail "searchlight 1 x 1"
if mpi 2 "$exe" "${half[@]}" --threads 1 --out half2.h5 >/dev/null 2>half2.err &&
  "$same" half1.h5 half2.h5; then pass; else fail "searchlight 2 x 1: $(cat half2.err)"; fi

# Stopped on one process after 4 batches, finished on two ranks of two threads.
"$exe" "${run[@]}" --threads 1 --out resumed.h5 --checkpoint-interval 4b >/dev/null 2>&1 &
pid=$!
for _ in $(seq 200); do [ -e resumed.h5.checkpoint ] && break; sleep 0.05; done
kill -INT $pid
wait $pid
if [ -e resumed.h5.checkpoint ] &&
  mpi 2 "$exe" "${run[@]}" --threads 2 --out resumed.h5 --resume >/dev/null 2>resume.err &&
  "$same" 1x1.h5 resumed.h5 >/dev/null; then pass; else
  fail "resume on 2 ranks: $(cat resume.err)"; fi

# Bad input: one message (from rank 0), exit 2, no file.
if ! mpi 2 "$exe" simulate --albedo 2 --photons 1000 --batches 4 --out bad.h5 >/dev/null 2>bad.err &&
  [ "$(grep -c medium.albedo bad.err)" -eq 1 ] && [ ! -e bad.h5 ]; then pass; else
  fail "bad input under mpirun: $(cat bad.err)"; fi

report "mpi runs"
