#!/usr/bin/env bash
# A short run's fixed costs, interleaved over the programs given:
#
#   bench/startup.sh REPS SCATTERLAB [NAME=SCATTERLAB ...]
#
# For each program, REPS times each (the first as given is called "new"):
#   version      `scatterlab --version`: loading the program and its libraries, their static
#                initialisers and the command line, and nothing else (wall time);
#   simulate     the default scene (radiance on the default grid, 64 batches), 100 photons;
#   searchlight  the default half-space (fluence, R_d and the analytic models beside them),
#                100 photons;
# and for the two runs, the start-up (from the exec to the first photon: to the run's first
# OpenMP parallel region, the batch runner's, seen by a shim preloaded with LD_PRELOAD) and the
# whole run (to the process's exit). Medians in milliseconds; each includes the shell's fork of
# the process (about 1 ms here).
set -euo pipefail
reps=$1
shift
programs=()
for spec in "$@"; do
  case $spec in
    *=*) programs+=("$spec") ;;
    *) programs+=("new=$spec") ;;
  esac
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The shim: prints the milliseconds since $STARTUP_T0 (ns) at the first parallel region and at
# exit, then hands the region to libgomp.
cat >"$work/shim.c" <<'C'
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
static double since_start(void) {
  struct timespec now;
  clock_gettime(CLOCK_REALTIME, &now);
  const char* t0 = getenv("STARTUP_T0");
  return ((double)now.tv_sec * 1e9 + (double)now.tv_nsec - atof(t0 ? t0 : "0")) / 1e6;
}
void GOMP_parallel(void (*fn)(void*), void* data, unsigned threads, unsigned flags) {
  static int seen = 0;
  if (!seen++) fprintf(stderr, "startup_first_photon_ms %.3f\n", since_start());
  void (*next)(void (*)(void*), void*, unsigned, unsigned) = dlsym(RTLD_NEXT, "GOMP_parallel");
  next(fn, data, threads, flags);
}
__attribute__((destructor)) static void at_exit(void) {
  fprintf(stderr, "startup_exit_ms %.3f\n", since_start());
}
C
cc -O2 -shared -fPIC "$work/shim.c" -o "$work/shim.so" -ldl

: >"$work/times"
for ((rep = 1; rep <= reps; ++rep)); do
  for spec in "${programs[@]}"; do
    name=${spec%%=*} exe=${spec#*=}
    start=$EPOCHREALTIME
    "$exe" --version >/dev/null
    end=$EPOCHREALTIME
    awk -v n="$name" -v a="$start" -v b="$end" 'BEGIN{printf "%s version %.3f\n", n, (b - a) * 1e3}' \
      >>"$work/times"
    for command in simulate searchlight; do
      rm -f "$work/run.h5"
      STARTUP_T0=$(date +%s%N) LD_PRELOAD=$work/shim.so \
        "$exe" "$command" --photons 100 --out "$work/run.h5" 2>"$work/stderr" >/dev/null
      awk -v n="$name" -v c="$command" '
        /^startup_first_photon_ms/ { printf "%s %s_start-up %s\n", n, c, $2 }
        /^startup_exit_ms/ { printf "%s %s_whole %s\n", n, c, $2 }' "$work/stderr" >>"$work/times"
    done
  done
done

sort -k1,1 -k2,2 -k3,3g "$work/times" | awk '
  function flush() {
    if (n == 0) return
    m = (n % 2) ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
    printf "%-8s %-22s %8.1f ms (%d runs, %.1f-%.1f)\n", p, w, m, n, v[1], v[n]
    n = 0
  }
  { if ($1 != p || $2 != w) { flush(); p = $1; w = $2 } v[++n] = $3 }
  END { flush() }'
