#!/usr/bin/env bash
# Usage: bssrdf_render_runs.sh SCATTERLAB SOURCE_DIR
# `scatterlab render --method bssrdf` end to end: each diffusion model writes the OpenEXR, the PNG
# and the HDF5 of the per-point exitance (points whose areas sum to the mesh's, exitance with
# units); a medium per channel gives three channels; bad flags get one error naming the flag,
# exit status 2, and no file.
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

scene=$source_dir/data/scenes/bssrdf-milk.toml
small=(--width 12 --height 10 --points 600 --relaxation 5 --threads 2)

for model in dipole better_dipole quantized_diffusion; do
  if "$exe" render "$scene" --method bssrdf --model "$model" "${small[@]}" \
       --out "$work/$model.exr" >"$work/stdout" 2>"$work/stderr" \
     && [ -s "$work/$model.exr" ] && [ -s "$work/$model.png" ] && [ -s "$work/$model.h5" ] \
     && grep -q "bssrdf $model: 12x10, 3 channel(s), 600 points" "$work/stdout"; then
    pass
  else
    fail "$model: $(cat "$work/stdout" "$work/stderr")"
  fi
done

# The file: 600 points, areas that sum to the sphere's (4 pi r^2 up to the tessellation), the
# exitance per channel, units on every dataset, and the settings.
if /usr/bin/python3 - "$work/better_dipole.h5" <<'PY'; then pass; else fail "point file"; fi
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
p = f["points"]
assert p["position"].shape == (600, 3) and p["normal"].shape == (600, 3)
assert p["exitance"].shape == (600, 3)
for name in ("position", "normal", "area", "irradiance", "exitance"):
    assert "units" in p[name].attrs, name
assert p["irradiance"].attrs["units"] == "W mm^-2"
area = p["area"][...].sum()
assert abs(area - 4 * np.pi * 2.0**2) < 0.01 * 4 * np.pi * 2.0**2, area
assert (p["irradiance"][...] >= 0).all() and (p["irradiance"][...] > 0).any()
assert (p["exitance"][...] > 0).all()
assert f["parameters"].attrs["model"] == "better_dipole"
assert f["parameters"].attrs["occlusion"] == 1
PY

# Without occlusion and with clustering off, the same points get at least as much light.
if "$exe" render "$scene" --method bssrdf "${small[@]}" --no-occlusion --cluster-angle 0 \
     --out "$work/open.exr" >"$work/stdout" 2>"$work/stderr" \
   && grep -q "occlusion off" "$work/stdout"; then
  pass
  if /usr/bin/python3 - "$work/better_dipole.h5" "$work/open.h5" <<'PY'; then pass; else fail "occlusion off"; fi
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1], "r")["points/irradiance"][...]
b = h5py.File(sys.argv[2], "r")["points/irradiance"][...]
assert (b >= a).all()
PY
else
  fail "--no-occlusion: $(cat "$work/stderr")"
fi

# Bad input: one error naming the flag, exit status 2, nothing written.
args=("$scene" --width 4 --height 4 --points 50 --relaxation 1)
expect_refused "unknown model" "--model" render "${args[@]}" --method bssrdf --model tripole \
  --out bad.exr
expect_refused "no points" "--points" render "${args[@]}" --method bssrdf --points 0 --out bad.exr
expect_refused "negative cluster angle" "--cluster-angle" render "${args[@]}" --method bssrdf \
  --cluster-angle -0.5 --out bad.exr
expect_refused "negative relaxation" "--relaxation" render "${args[@]}" --method bssrdf \
  --relaxation -1 --out bad.exr
expect_refused "bssrdf flag with another method" "--model" render "${args[@]}" \
  --method holzschuch --model dipole --out bad.exr
expect_refused "a floor" "floor" render "$source_dir/data/scenes/milk-sphere.toml" --width 4 \
  --height 4 --method bssrdf --points 50 --out bad.exr
expect_refused "no clustering, too much work" "--cluster-angle" render "$scene" --width 16384 \
  --height 16384 --method bssrdf --points 4000000 --cluster-angle 0 --out bad.exr
expect_refused "not .exr" "--out" render "${args[@]}" --method bssrdf --out bad.png

report bssrdf_render_runs
