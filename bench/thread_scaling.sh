#!/usr/bin/env bash
# Whole-run thread scaling of the transport, and the machine's own ceiling beside it.
#
#   bench/thread_scaling.sh OUT.tsv REPS SCATTERLAB [NAME=SCATTERLAB ...]
#
# Runs, interleaved over REPS repetitions and the programs given (each NAME=PATH, the first as
# given is called "new"), two scenes on 1, 2, 4, ... threads up to the machine's hardware threads:
#   beam       the default job (pencil beam, albedo 0.5, g 0.9, radiance on the default grid)
#   half_space MCML's case a (albedo 0.99, g 0, eta 1) with its fluence tally
# and, as the ceiling, N one-thread processes of 1/N of the photons each, started together (what
# the machine gives independent work, whatever the program's threading: its transport_s is the
# slowest process's). Every line of OUT.tsv is "scene program threads rep transport_s wall_s",
# transport_s being the time the program prints for its batches; a table of medians and
# speed-ups over one thread ends the output. Photon counts: BEAM_PHOTONS (default 3e7) and
# HALF_SPACE_PHOTONS (6e6); THREADS="1 16" runs those thread counts only.
set -euo pipefail
out=$1 reps=$2
shift 2
programs=()
for spec in "$@"; do
  case $spec in
    *=*) programs+=("$spec") ;;
    *) programs+=("new=$spec") ;;
  esac
done
cores=$(nproc)
threads=()
for ((t = 1; t <= cores; t *= 2)); do threads+=("$t"); done
[ "${threads[-1]}" -eq "$cores" ] || threads+=("$cores")
if [ -n "${THREADS:-}" ]; then read -ra threads <<<"$THREADS"; fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

args_of() {  # args_of SCENE PHOTONS: the command line of a scene
  case $1 in
    beam) echo "simulate --photons $2 --seed 1" ;;
    half_space) echo "searchlight --eta 1 --albedo 0.99 --g 0 --tallies fluence --photons $2 --seed 1" ;;
  esac
}
photons_of() { [ "$1" = beam ] && echo "${BEAM_PHOTONS:-3e7}" || echo "${HALF_SPACE_PHOTONS:-6e6}"; }

# transport_seconds STDOUT...: the longest of the runs' transport times, as photons over the
# printed rate (3 digits; the printed seconds have 2 decimals).
transport_seconds() {
  sed -n 's/^ *\([0-9]*\) photons in [0-9]* batches on .*s (\([0-9.e+]*\) photons\/s.*/\1 \2/p' \
    "$@" | awk '{ s = $1 / $2; if (s > m) m = s } END { printf "%.4g", m }'
}

# run SCENE NAME PATH THREADS REP: one run, its line appended to OUT.
run() {
  local scene=$1 name=$2 exe=$3 t=$4 rep=$5 start end seconds
  start=$EPOCHREALTIME
  # shellcheck disable=SC2046
  "$exe" $(args_of "$scene" "$(photons_of "$scene")") --threads "$t" --out "$work/run.h5" \
    >"$work/stdout"
  end=$EPOCHREALTIME
  seconds=$(transport_seconds "$work/stdout")
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$scene" "$name" "$t" "$rep" "$seconds" \
    "$(awk -v a="$start" -v b="$end" 'BEGIN{printf "%.3f", b - a}')" >>"$out"
  rm -f "$work/run.h5"
}

# ceiling SCENE PATH N REP: N one-thread processes of 1/N of the photons, together.
ceiling() {
  local scene=$1 exe=$2 n=$3 rep=$4 start end photons
  photons=$(awk -v p="$(photons_of "$scene")" -v n="$n" 'BEGIN{printf "%.0f", p / n}')
  start=$EPOCHREALTIME
  for ((i = 0; i < n; ++i)); do
    # shellcheck disable=SC2046
    "$exe" $(args_of "$scene" "$photons") --seed $((i + 1)) --threads 1 \
      --out "$work/c$i.h5" >"$work/c$i.out" &
  done
  wait
  end=$EPOCHREALTIME
  printf '%s\tprocesses\t%s\t%s\t%s\t%s\n' "$scene" "$n" "$rep" \
    "$(transport_seconds "$work"/c*.out)" \
    "$(awk -v a="$start" -v b="$end" 'BEGIN{printf "%.3f", b - a}')" >>"$out"
  rm -f "$work"/c*.h5 "$work"/c*.out
}

: >"$out"
for ((rep = 1; rep <= reps; ++rep)); do
  for scene in beam half_space; do
    for t in "${threads[@]}"; do
      for spec in "${programs[@]}"; do run "$scene" "${spec%%=*}" "${spec#*=}" "$t" "$rep"; done
      ceiling "$scene" "${programs[0]#*=}" "$t" "$rep"
    done
  done
done

# Medians per (scene, program, threads), and the speed-up over the same program on one thread
# (plain awk: the device machine's may not be GNU awk).
sort -t$'\t' -k1,1 -k2,2 -k3,3n -k5,5g "$out" | awk -F'\t' '
  function flush() {
    if (n == 0) return
    m = (n % 2) ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
    if (t == 1) one[s, p] = m
    printf "%-10s %-9s %3d threads: %8.3f s  %6.2fx\n", s, p, t, m, one[s, p] / m
    n = 0
  }
  { if ($1 != s || $2 != p || $3 != t) { flush(); s = $1; p = $2; t = $3 } v[++n] = $5 }
  END { flush() }'
