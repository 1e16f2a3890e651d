#!/usr/bin/env bash
# Usage: progress_runs.sh SCATTERLAB
# Progress off a terminal: a plain line on standard error every --log-interval seconds (never on
# standard output), none with 0, bad intervals refused. After an interrupted and resumed run the
# file and the summary count the whole run's time and photons, and this session's apart. Every
# figure of merit in the file is 1 / (R^2 T) of the file's own mean, stderr and wall_seconds.
set -u
exe=$(realpath "$1")
source "$(dirname "$0")/harness.sh"

# A second or more on one thread, in 24 batches.
run=(simulate --photons 12000000 --batches 24 --threads 1 --seed 5 --theta-bins 6 --phi-bins 8)
line='^simulate: [0-9]+/24 batches, [0-9.e+-]+ photons/s, [0-9.e+-]+ events/photon, [0-9.]+ (s|min|h) elapsed, ETA ([0-9.]+ (s|min|h)|--)$'

# Lines every 0.05 s, off a terminal (standard error is a file here): one as the run starts, then
# a line after the first batch and after the first batch to end after each interval, so between
# 2 and 24 of them.
"$exe" "${run[@]}" --out logged.h5 --log-interval 0.05 >logged.out 2>logged.err ||
  fail "logged run: $(cat logged.err)"
lines=$(grep -cE "$line" logged.err)
if [ "$(head -1 logged.err)" = "simulate: 0/24 batches, started; a line every 0.05 s" ] &&
  [ "$lines" -ge 2 ] && [ "$lines" -le 24 ] && [ "$((lines + 1))" -eq "$(grep -c . logged.err)" ]
then
  pass
else
  fail "expected a first line, then 2 to 24 progress lines and nothing else on stderr: $(cat logged.err)"
fi
# The default: a first line at once, then one every 10 s (none, unless the machine is loaded).
"$exe" "${run[@]}" --out default.h5 >default.out 2>default.err || fail "default run"
if [ "$(head -1 default.err)" = "simulate: 0/24 batches, started; a line every 10 s" ] &&
  [ "$(tail -n +2 default.err | grep -cvE "$line")" -eq 0 ]; then pass; else
  fail "default progress: $(cat default.err)"; fi
if grep -q "batches," logged.out; then fail "progress on standard output: $(cat logged.out)"; else pass; fi
# Each line's events per photon is that of the batches done: within 1 % of the whole run's (the
# summary's scattering events over its photons), with half a million photons a batch.
if python3 - logged.out logged.err <<'PY'
import re, sys
summary, err = open(sys.argv[1]).read(), open(sys.argv[2]).read()
m = re.search(r"([0-9]+) photons in .*?([0-9.e+]+) scattering events", summary)
whole = float(m.group(2)) / float(m.group(1))
lines = [float(v) for v in re.findall(r"([0-9.e+-]+) events/photon", err)]
assert lines and all(abs(v / whole - 1) < 0.01 for v in lines), (whole, lines)
PY
then pass; else fail "events per photon of the progress lines against the summary's"; fi

# 0: no lines.
"$exe" "${run[@]}" --out quiet.h5 --log-interval 0 >quiet.out 2>quiet.err || fail "quiet run"
if [ -s quiet.err ]; then fail "--log-interval 0 wrote: $(cat quiet.err)"; else pass; fi

# Bad intervals: one line naming the flag, exit 2, nothing written; on every command that has it.
for value in -1 nan inf abc '' 1e999 5m; do
  expect_refused "simulate --log-interval '$value'" --log-interval \
    "${run[@]}" --out bad.h5 --log-interval "$value"
done
expect_refused "searchlight --log-interval -1" --log-interval \
  searchlight --photons 1000 --out bad.h5 --log-interval -1
expect_refused "fit --log-interval -1" --log-interval fit logged.h5 --log-interval -1
expect_refused "render --log-interval -1" --log-interval render scene.toml --log-interval -1
expect_refused "report --log-interval -1" --log-interval report --quick --log-interval -1
expect_refused "validate deon --log-interval -1" --log-interval validate deon --log-interval -1
expect_refused "validate searchlight --log-interval -1" --log-interval \
  validate searchlight --log-interval -1

# wait_for FILE: until it exists (at most ~20 s).
wait_for() { for _ in $(seq 1000); do [ -e "$1" ] && return 0; sleep 0.02; done; return 1; }

# Interrupted after a checkpoint, then resumed.
"$exe" "${run[@]}" --out resumed.h5 --checkpoint-interval 4b >first.out 2>first.err &
pid=$!
wait_for resumed.h5.checkpoint
kill -INT $pid
wait $pid
status=$?
[ $status -eq 130 ] || fail "interrupt: exit $status, $(cat first.err)"
"$exe" "${run[@]}" --out resumed.h5 --resume --log-interval 0.05 >resume.out 2>resume.err ||
  fail "resume: $(cat resume.err)"
if grep -qE '^simulate: [0-9]+/24 batches \([0-9]+ resumed\), ' resume.err &&
  grep -qE '^simulate: [0-9]+/24 batches \([0-9]+ resumed\), started' resume.err; then pass; else
  fail "resumed progress lines do not say what was resumed: $(cat resume.err)"
fi
if grep -q "this session: " resume.out; then pass; else
  fail "no session figures in the summary: $(cat resume.out)"
fi

if ! /usr/bin/python3 -c 'import h5py' 2>"$scratch/h5py.err"; then
  fail "no h5py for /usr/bin/python3: $(cat "$scratch/h5py.err")"
  report "cli.progress"
  exit
fi
/usr/bin/python3 - resumed.h5 resume.out logged.h5 >checks.out 2>&1 <<'PY' || fail "$(cat checks.out)"
import re
import sys

import h5py
import numpy as np

path, summary, uninterrupted = sys.argv[1], open(sys.argv[2]).read(), sys.argv[3]
problems = []
with h5py.File(path, "r") as f:
    a = f.attrs
    total, session = float(a["wall_seconds"]), float(a["session_wall_seconds"])
    photons, session_photons = int(a["photons_run"]), int(a["session_photons_run"])
    if not (session > 0 and total > session):
        problems.append(f"wall_seconds {total} not above session_wall_seconds {session}")
    if not (0 < session_photons < photons == int(f["parameters"].attrs["photons"])):
        problems.append(f"photons_run {photons}, session_photons_run {session_photons}")
    # The summary's rate is the whole run's: photons_run / wall_seconds (printed to 3 digits).
    m = re.search(r"photons in \d+ batches on .*: ([0-9.]+) s \(([0-9.e+]+) photons/s", summary)
    if not m:
        problems.append("no timing line in the summary")
    else:
        printed = float(m.group(2))
        if abs(printed - photons / total) > 0.006 * printed:
            problems.append(f"printed rate {printed}, photons_run / wall_seconds {photons / total}")
        if abs(float(m.group(1)) - total) > 0.006:
            problems.append(f"printed time {m.group(1)} s, wall_seconds {total}")
for name in (path, uninterrupted):
    with h5py.File(name, "r") as f:
        wall = float(f.attrs["wall_seconds"])
        if float(f.attrs["session_wall_seconds"]) > wall:
            problems.append(f"{name}: session longer than the run")
        merits = f["figures_of_merit"]
        for wanted in ("absorbed", "fluence", "radiance"):
            if wanted not in merits:
                problems.append(f"{name}: no figure of merit for {wanted}")
        for tally in merits:
            d = merits[tally]
            mean = np.ravel(f["tallies"][tally]["mean"][()])
            err = np.ravel(f["tallies"][tally]["stderr"][()])
            nonzero = mean != 0
            r = np.median(err[nonzero] / np.abs(mean[nonzero]))
            expected = 1.0 / (r * r * wall)
            if d.attrs["units"] != "1/s" or not d.attrs["description"]:
                problems.append(f"{name}: {tally}: units or description missing")
            if abs(d[()] - expected) > 1e-12 * expected:
                problems.append(f"{name}: {tally}: figure of merit {d[()]}, 1/(R^2 T) {expected}")
print("\n".join(problems) if problems else "ok")
sys.exit(1 if problems else 0)
PY
grep -qx ok checks.out && pass

# The summary prints the figures of merit.
if grep -qE "figure of merit 1/\(R\^2 T\), 1/s: absorbed [0-9.e+]+" logged.out; then pass; else
  fail "no figures of merit in the summary: $(cat logged.out)"
fi

report "cli.progress"
