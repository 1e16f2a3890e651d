#!/usr/bin/env bash
# scatterlab explore refuses bad input before it serves: one line naming the flag or the file,
# exit status 2, within a minute (no server left running), nothing in the working directory
# touched. Usage: cli_errors.sh SCATTERLAB
set -uo pipefail
exe=$1
source "$(dirname "$0")/../cli/harness.sh"
mkdir bad empty
printf 'name = "b"\nR_d = "exp(-r"\n' >bad/broken.toml
printf 'name = "b"\n[[parameter]]\nname = "k"\nmin = 2\nmax = 1\ndefault = 1\n' >bad/range.toml

expect_refused "no models folder" "models" explore --port 0 --models "$work/none"
expect_refused "no open folder" "open" explore --port 0 --open "$work/none"
expect_refused "port out of range" "--port" explore --port 70000
expect_refused "not a port" "--port" explore --port http
expect_refused "a page folder without the page" "page" explore --port 0 --page "$work/empty"
expect_refused "a bad model file" "broken.toml:2: R_d" explore --port 0 --models "$work/bad"
rm bad/broken.toml
expect_refused "a parameter's range" "range.toml:2: parameter.k" explore --port 0 --models "$work/bad"
expect_refused "an unknown flag" "--prot" explore --prot 8000

# A port in use: the second explorer is refused, the first keeps serving and ends on SIGINT.
"$exe" explore --port 0 >"$scratch/first" 2>&1 &
first=$!
for _ in $(seq 50); do grep -q "http://" "$scratch/first" && break; sleep 0.1; done
port=$(grep -o "127.0.0.1:[0-9]*" "$scratch/first" | cut -d: -f2)
if [ -n "$port" ]; then
  expect_refused "a port in use" "port: cannot listen on 127.0.0.1:$port" explore --port "$port"
else
  fail "the first explorer did not start: $(cat "$scratch/first")"
fi
kill -INT "$first"
if wait "$first" && grep -q "stopped" "$scratch/first"; then pass; else
  fail "the explorer did not end cleanly on SIGINT: $(cat "$scratch/first")"
fi
report "explore bad input"
