#!/usr/bin/env bash
# Usage: lit_mesh_runs.sh SCATTERLAB SOURCE_DIR
# Objects bounded by a mesh from the command line: simulate runs data/scenes/lit-mesh.toml (and
# a beam, a sphere of light, an OBJ file), prints the energy balance, and writes
# the exitance per triangle with the mesh in /parameters/mesh; merge refuses runs on another
# mesh; bad mesh scenes get one error naming the key, exit status 2, no file.
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

scene=$source_dir/data/scenes/lit-mesh.toml
small=(--photons 20000 --batches 8 --threads 2)

if "$exe" simulate --scene "$scene" "${small[@]}" --out "$work/mesh.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  pass
  if grep -Eq "energy per W incident: reflected_at_entry .*, exited .*, absorbed .* total 1\.000000" \
    "$work/stdout"; then pass; else fail "energy line: $(cat "$work/stdout")"; fi
  if grep -q "exitance \[3840\] per triangle" "$work/stdout"; then pass; else
    fail "summary: $(cat "$work/stdout")"; fi
  expect_info mesh "$work/mesh.h5" "geometry +mesh" "source +directional" \
    "exitance +\[3840\] \(triangle\), W mfp\^-2" "exitance_multiple" "reflected_at_entry +scalar"
  # The mesh is in the file, as many triangles as the exitance has values, and the exitance
  # times the areas is the power that left.
  if /usr/bin/python3 - "$work/mesh.h5" <<'PY'; then pass; else fail "mesh datasets"; fi
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
mesh = f["parameters/mesh"]
assert mesh["positions"].shape[1] == 3 and mesh["triangles"].shape == (3840, 3)
assert mesh["positions"].attrs["units"] == "mfp"
exitance = f["tallies/exitance/mean"][...]
assert exitance.shape == (3840,)
assert abs((exitance * mesh["area"][...]).sum() - f["tallies/exited/mean"][()]) < 1e-12
PY
else
  fail "lit-mesh.toml: $(cat "$work/stderr")"
fi

# A beam and a sphere of light, in mm: the file says which.
cat >"$work/beam.toml" <<'TOML'
[geometry]
type = "mesh"
eta = 1.4
[mesh]
shape = "box"
half_size = [1.0, 1.0, 0.5]
[medium]
sigma_t = 2.0
albedo = 0.9
length_unit = "mm"
[source]
type = "beam"
origin = [0.2, 0.0, -3.0]
direction = [0.3, 0.0, 1.0]
TOML
if "$exe" simulate "$work/beam.toml" "${small[@]}" --out "$work/beam.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  expect_info beam "$work/beam.h5" "source +beam" "length_unit +mm" \
    "exitance +\[12\] \(triangle\), W mm\^-2 per W incident"
else
  fail "beam: $(cat "$work/stderr")"
fi
sed -e 's/type = "beam"/type = "sphere"/' -e 's/^origin.*/position = [0, 0, -4]/' \
  -e 's/^direction.*/radius = 1.0/' "$work/beam.toml" >"$work/light.toml"
if "$exe" simulate "$work/light.toml" "${small[@]}" --out "$work/light.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  expect_info light "$work/light.h5" "source +sphere" "light_sphere +radius 1 about \(0, 0, -4\)"
else
  fail "sphere of light: $(cat "$work/stderr")"
fi

# An OBJ file, relative to the scene: a tetrahedron.
cat >"$work/tet.obj" <<'OBJ'
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
OBJ
printf '[geometry]\ntype = "mesh"\n[mesh]\nshape = "obj"\npath = "tet.obj"\nnormals = "flat"\n' \
  >"$work/tet.toml"
if "$exe" simulate "$work/tet.toml" "${small[@]}" --out "$work/tet.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  if grep -q "OBJ file .*tet.obj" "$work/stdout"; then pass; else
    fail "tet summary: $(cat "$work/stdout")"; fi
else
  fail "tet: $(cat "$work/stderr")"
fi

# Runs on one mesh merge; merge refuses runs on another (a value of /parameters/mesh differs).
"$exe" simulate --scene "$scene" "${small[@]}" --seed 3 --out "$work/again.h5" >/dev/null 2>&1
if "$exe" merge "$work/mesh.h5" "$work/tet.h5" --out "$work/merged.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  fail "merge of two meshes accepted"
elif grep -q "parameters" "$work/stderr" && [ ! -e "$work/merged.h5" ]; then pass; else
  fail "merge of two meshes: $(cat "$work/stderr")"
fi
if "$exe" merge "$work/mesh.h5" "$work/again.h5" --out "$work/merged.h5" >"$work/stdout" \
  2>"$work/stderr"; then pass; else fail "merge of one mesh: $(cat "$work/stderr")"; fi

# Bad mesh scenes name their key and write nothing.
small=(--photons 1000 --batches 4)
bad() {
  local name=$1 field=$2 text=$3
  printf '%s\n' "$text" >"$work/$name.toml"
  expect_command_error simulate "$name" "$field" "$work/$name.toml"
}
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$work/open.obj"
bad open mesh $'[geometry]\ntype = "mesh"\n[mesh]\nshape = "obj"\npath = "open.obj"'
bad no_mesh mesh $'[geometry]\ntype = "mesh"'
bad shape mesh.shape $'[geometry]\ntype = "mesh"\n[mesh]\nshape = "teapot"'
bad radius geometry.radius $'[geometry]\ntype = "mesh"\nradius = 2\n[mesh]\nshape = "sphere"'
bad grid grid $'[geometry]\ntype = "mesh"\n[mesh]\nshape = "sphere"\n[grid]\npsi = { bins = 4 }'
bad pole source.type $'[geometry]\ntype = "mesh"\n[mesh]\nshape = "sphere"\n[source]\ntype = "pole_beam"'
bad inside source.origin $'[geometry]\ntype = "mesh"\n[mesh]\nshape = "sphere"\n[source]\ntype = "beam"\norigin = [0, 0, 0.2]'
bad light_inside source.position $'[geometry]\ntype = "mesh"\n[mesh]\nshape = "sphere"\n[source]\ntype = "sphere"\nposition = [0, 0, 0]'
bad overlap source.radius $'[geometry]\ntype = "mesh"\n[mesh]\nshape = "sphere"\n[source]\ntype = "sphere"\nposition = [0, 0, -1.5]\nradius = 1'
bad sphere_light source.type $'[geometry]\ntype = "sphere"\n[source]\ntype = "sphere"'
bad mesh_on_sphere mesh $'[geometry]\ntype = "sphere"\n[mesh]\nshape = "sphere"'

report lit_mesh_runs
