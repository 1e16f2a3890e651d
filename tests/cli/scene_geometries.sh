#!/usr/bin/env bash
# Usage: scene_geometries.sh SCATTERLAB SOURCE_DIR
# One front door: scatterlab simulate runs a scene of every geometry, searchlight is simulate
# for the half-space, and a sweep works for every geometry.
#   - simulate on the shipped half-space scene writes the same tallies, bit for bit, as
#     searchlight on it (the same reader, flags and runner);
#   - a slab whose second layer's thickness is a list, and a sphere whose radius is a list, each
#     run one file per value from one scene file, and a second run skips them as done;
#   - a flag that the scene's geometry does not take is refused, naming the flag and the
#     geometry; searchlight refuses a scene of another geometry.
set -u
exe=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

tiny=(--photons 4000 --batches 4 --threads 1 --seed 3)
half=(--r-bins 4 --z-bins 4 --theta-bins 3)
"$exe" simulate "$src/data/scenes/searchlight.toml" "${tiny[@]}" "${half[@]}" --out s.h5 >s.txt ||
  fail "simulate on the half-space scene"
"$exe" searchlight "$src/data/scenes/searchlight.toml" "${tiny[@]}" "${half[@]}" --out l.h5 >l.txt ||
  fail "searchlight on the half-space scene"
# info prints every tally's sums; the files differ only in their provenance (the command).
same() { "$exe" info "$1" | grep -v "^file\|^command\|^created\|^wall time"; }
if diff <(same s.h5) <(same l.h5) >"$scratch/diff"; then pass; else
  fail "simulate and searchlight on one half-space scene differ: $(head "$scratch/diff")"; fi
if grep -q "half-space, albedo" s.txt && grep -q "diffuse_reflectance" <("$exe" info s.h5); then
  pass
else
  fail "simulate's half-space summary or file: $(cat s.txt)"
fi

cat >slab.toml <<'TOML'
[geometry]
type = "slab"
length_unit = "cm"
[[layers]]
mu_a = 1.0
mu_s = 100.0
g = 0.9
n = 1.37
thickness = 0.01
[[layers]]
mu_a = 0.5
mu_s = 50.0
g = 0.8
n = 1.37
thickness = [0.02, 0.1]
[grid]
r = { max = 0.2, bins = 4 }
z = { max = 0.2, bins = 4 }
theta_o = { bins = 3 }
TOML
"$exe" simulate slab.toml "${tiny[@]}" --out slabs >slabs.txt || fail "slab sweep: $(cat slabs.txt)"
if [ -f slabs/thickness=0.02.h5 ] && [ -f slabs/thickness=0.1.h5 ]; then pass; else
  fail "slab sweep files: $(ls slabs)"; fi
# A thicker second layer transmits less: T_t (as each run's summary prints it) falls.
read -r thin thick < <(sed -nE 's/.*total_transmittance ([0-9.e+-]+) .*/\1/p' slabs.txt | xargs)
if awk -v a="$thin" -v b="$thick" 'BEGIN { exit !(a > b && b > 0) }'; then pass; else
  fail "T_t does not fall with the thickness: $thin, $thick"
fi
"$exe" simulate slab.toml "${tiny[@]}" --out slabs >again.txt || fail "slab sweep again"
if [ "$(grep -c "^skip" again.txt)" -eq 2 ]; then pass; else fail "done runs not skipped"; fi

cat >sphere.toml <<'TOML'
[geometry]
type = "sphere"
radius = [0.5, 2.0]
eta = 1.3
[grid]
psi = { bins = 6 }
TOML
"$exe" simulate sphere.toml "${tiny[@]}" --out spheres >spheres.txt ||
  fail "sphere sweep: $(cat spheres.txt)"
if [ -f spheres/radius=0.5.h5 ] && [ -f spheres/radius=2.h5 ]; then pass; else
  fail "sphere sweep files: $(ls spheres)"; fi

# Flags a geometry does not take, and searchlight on another geometry.
expect_refused "incidence on a sphere" "--incidence.*sphere" \
  simulate "$src/data/scenes/lit-sphere.toml" --incidence 30
expect_refused "fold-phi on a half-space" "--fold-phi.*half_space" \
  simulate "$src/data/scenes/searchlight.toml" --fold-phi
expect_refused "albedo on a slab" "--albedo.*slab" simulate slab.toml --albedo 0.5 --out x
expect_refused "source for searchlight" "--source.*half_space" searchlight --source point
expect_refused "searchlight on a sphere" "geometry.type.*sphere" \
  searchlight "$src/data/scenes/lit-sphere.toml"

report "scene geometries"
