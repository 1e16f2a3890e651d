#!/usr/bin/env bash
# Usage: lit_sphere_runs.sh SCATTERLAB SOURCE_DIR
# The lit sphere from the command line: simulate runs data/scenes/lit-sphere.toml (and a pole
# beam, and a material in mm), prints the energy balance, and writes the exitance against the
# angle from the lit pole with its grid and parameters; the infinite medium's flags are refused
# for a sphere scene, and bad sphere scenes get one error naming the key, exit status 2, no file.
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

scene=$source_dir/data/scenes/lit-sphere.toml
small=(--photons 20000 --batches 8 --threads 2)

# The shipped scene: the summary's energy balance sums to 1, the file holds the sphere.
if "$exe" simulate --scene "$scene" "${small[@]}" --out "$work/sphere.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  pass
  if grep -Eq "energy per W incident: reflected_at_entry .*, exited .*, absorbed .* total 1\.000000" \
    "$work/stdout"; then pass; else fail "energy line: $(cat "$work/stdout")"; fi
  expect_info sphere "$work/sphere.h5" "geometry +sphere" "source +directional" "radius +1$" \
    "eta +1\.3" "psi +36 bins in \[0, 3\.14159\] rad" \
    "exitance +\[36 x 1\] \(psi,azimuth\), W mfp\^-2" \
    "exitance_multiple" "reflected_at_entry +scalar"
else
  fail "lit-sphere.toml: $(cat "$work/stderr")"
fi

# Flags of the medium and the run override the scene; a pole beam's reflection is exact.
cat >"$work/pole.toml" <<'TOML'
[geometry]
type = "sphere"
radius = 3.0
[source]
type = "pole_beam"
TOML
if "$exe" simulate "$work/pole.toml" "${small[@]}" --albedo 0.5 --g 0.8 --out "$work/pole.h5" \
  >"$work/stdout" 2>"$work/stderr"; then
  expect_info pole "$work/pole.h5" "source +pole_beam" "albedo +0\.5$" "g +0\.8$" "radius +3$"
  if grep -q "reflected_at_entry 0.017013" "$work/stdout"; then pass; else
    fail "pole beam: F(1) at eta 1.3 is 0.0170132: $(cat "$work/stdout")"; fi
else
  fail "pole beam: $(cat "$work/stderr")"
fi

# A beam from outside, off the axis: the file says where it came from.
cat >"$work/beam.toml" <<'TOML'
[geometry]
type = "sphere"
radius = 1.0
[source]
type = "beam"
origin = [0.5, 0.0, -3.0]
direction = [0, 0, 1]
[grid]
azimuth = { bins = 8 }
TOML
if "$exe" simulate "$work/beam.toml" "${small[@]}" --out "$work/beam.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  expect_info beam "$work/beam.h5" "source +beam" "beam +from \(0\.5, 0, -3\) along \(0, 0, 1\)" \
    "azimuth +8 bins in \[0, 6\.28319\] rad" "exitance +\[36 x 8\] \(psi,azimuth\)"
else
  fail "beam: $(cat "$work/stderr")"
fi

# A material: its table's eta and mm, the radius in mm.
cat >"$work/marble.toml" <<'TOML'
[geometry]
type = "sphere"
radius = 2.0
[medium]
material = "marble"
channel = "green"
TOML
if "$exe" simulate "$work/marble.toml" --photons 2000 --batches 4 --threads 2 \
  --out "$work/marble.h5" >"$work/stdout" 2>"$work/stderr"; then
  expect_info marble "$work/marble.h5" "length_unit +mm" "material +marble" "radius +2$" \
    "exitance .*W mm\^-2 per W incident"
else
  fail "marble: $(cat "$work/stderr")"
fi

# The infinite medium's flags are not the sphere's; bad scenes name their key.
small=(--photons 1000 --batches 4)
expect_command_error simulate r_bins --r-bins "$scene" --r-bins 10
expect_command_error simulate source --source "$scene" --source point
expect_command_error simulate tallies --tallies "$scene" --tallies fluence
bad() {
  local name=$1 field=$2 text=$3
  printf '%s\n' "$text" >"$work/$name.toml"
  expect_command_error simulate "$name" "$field" "$work/$name.toml"
}
bad radius geometry.radius $'[geometry]\ntype = "sphere"\nradius = -1'
bad radius_typo geometry.radiuss $'[geometry]\ntype = "sphere"\nradiuss = 2'
bad eta geometry.eta $'[geometry]\ntype = "sphere"\neta = 50'
bad light source.type $'[geometry]\ntype = "sphere"\n[source]\ntype = "laser"'
bad psi grid.psi.bins $'[geometry]\ntype = "sphere"\n[grid]\npsi = { bins = 0 }'
bad miss source.direction $'[geometry]\ntype = "sphere"\n[source]\ntype = "beam"\norigin = [0, 0, -3]\ndirection = [1, 0, 0]'
bad inside source.origin $'[geometry]\ntype = "sphere"\n[source]\ntype = "beam"\norigin = [0, 0, 0.5]'
bad not_beam source.origin $'[geometry]\ntype = "sphere"\n[source]\norigin = [0, 0, -3]'
bad vector source.direction $'[geometry]\ntype = "sphere"\n[source]\ntype = "beam"\ndirection = [0, 1]'
bad cube geometry.type $'[geometry]\ntype = "cube"'
if grep -q "sphere" "$work/stderr"; then pass; else
  fail "an unknown geometry does not list sphere: $(cat "$work/stderr")"; fi

report lit_sphere_runs
