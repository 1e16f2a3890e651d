#!/usr/bin/env bash
# Usage: scene_schema.sh SCATTERLAB SOURCE_DIR
# The scene's one table of keys (io/scene_schema.hpp), as users meet it:
#   - every shipped scene file that simulate reads validates against `scatterlab scene --schema`
#     (Draft 2020-12, python3-jsonschema), and so does a sweep of every geometry;
#   - what the reader refuses as a key, the schema refuses too: a misspelt key, another
#     geometry's key, a choice not among the choices;
#   - docs/scene-keys.md is `scatterlab scene --keys`, as committed.
set -u
exe=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

"$exe" scene --schema >schema.json || fail "scene --schema"
# check.py SCHEMA FILE...: prints "ok FILE" or "invalid FILE: why" for each TOML file.
cat >"$scratch/check.py" <<'PY'
import json, sys, tomllib
from jsonschema import Draft202012Validator
schema = json.load(open(sys.argv[1]))
Draft202012Validator.check_schema(schema)
validator = Draft202012Validator(schema)
for path in sys.argv[2:]:
    with open(path, "rb") as f:
        errors = list(validator.iter_errors(tomllib.load(f)))
    print(f"ok {path}" if not errors else f"invalid {path}: {errors[0].message}")
PY
check() { /usr/bin/python3 "$scratch/check.py" schema.json "$@"; }

# The shipped scenes of simulate (the others are render's: they have a camera).
for scene in "$src"/data/scenes/*.toml; do
  grep -q '^\[camera\]' "$scene" && continue
  if check "$scene" | grep -q "^ok"; then pass; else fail "$(check "$scene")"; fi
  "$exe" simulate "$scene" --photons 1000 --batches 2 --threads 1 --out-dir "out-$(basename "$scene" .toml)" \
    >/dev/null 2>"$scratch/err" || fail "simulate refuses $scene: $(cat "$scratch/err")"
done

printf '[geometry]\ntype = "slab"\n[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0.9\nn = 1.4\nthickness = [0.1, 0.2]\n' >slab-sweep.toml
printf '[geometry]\ntype = "sphere"\nradius = [1, 2]\n[source]\ntype = "beam"\norigin = [[0, 0, -3], [0.5, 0, -3]]\n' >sphere-sweep.toml
for good in slab-sweep sphere-sweep; do
  if check $good.toml | grep -q "^ok"; then pass; else fail "$(check $good.toml)"; fi
done

# Refused by the reader, and by the schema.
printf '[medium]\nalbdo = 0.5\n' >typo.toml
printf '[grid]\npsi = { bins = 4 }\n' >other-geometry.toml
printf '[geometry]\ntype = "slab"\n[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0.9\nn = 1.4\nthickness = 1\n[run]\nweighting = "russian"\n' >choice.toml
printf '[geometry]\ntype = "cube"\n' >cube.toml
for bad in typo other-geometry choice cube; do
  if check $bad.toml | grep -q "^invalid"; then pass; else fail "the schema accepts $bad.toml"; fi
  if "$exe" simulate $bad.toml --out x.h5 >/dev/null 2>&1; then fail "simulate accepts $bad.toml"; else
    pass; fi
done

if diff <("$exe" scene --keys) "$src/docs/scene-keys.md" >"$scratch/diff"; then pass; else
  fail "docs/scene-keys.md is not scatterlab scene --keys: $(head -5 "$scratch/diff")"; fi

report "scene schema"
