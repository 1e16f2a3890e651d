#!/usr/bin/env bash
# Usage: render_runs.sh SCATTERLAB SOURCE_DIR
# `scatterlab render` end to end: each method writes an OpenEXR and a PNG; bad input gets one
# clear error, a non-zero exit and no image.
set -u
exe=$1
source_dir=$2
source "$(dirname "$0")/harness.sh"
scene="$source_dir/data/scenes/tile.toml"

# Small images: the single-scatter solvers take minutes per 8x8 image under the sanitizers.
for method in straight walter holzschuch pathtrace volumetric; do
  if "$exe" render "$scene" --method "$method" --width 4 --height 4 --samples 2 \
       --light-samples 1 --out "$work/$method.exr" >stdout 2>stderr \
     && [ -s "$work/$method.exr" ] && [ -s "$work/$method.png" ] \
     && head -c 4 "$work/$method.exr" | od -An -tx1 | grep -q "76 2f 31 01" \
     && head -c 8 "$work/$method.png" | od -An -c | grep -q "P   N   G"; then
    pass
  else
    fail "$method: $(cat stderr)"
  fi
done

# The milk sphere in colour: an RGB PNG (colour type 2 in the IHDR chunk, byte 26).
milk="$source_dir/data/scenes/milk-sphere.toml"
if "$exe" render "$milk" --method volumetric --width 8 --height 6 --samples 2 \
     --out "$work/milk.exr" >stdout 2>stderr \
   && [ "$(od -An -tu1 -j25 -N1 "$work/milk.png" | tr -d ' ')" = 2 ] \
   && grep -q "exposure .* (auto)" stdout; then
  pass
else
  fail "milk sphere: $(cat stderr)"
fi

# expect_error NAME FIELD ARGS...
expect_error() {
  local name=$1 field=$2
  shift 2
  if "$exe" render "$@" --width 4 --height 4 --out "$work/$name.exr" >stdout 2>stderr; then
    fail "$name: exited 0"
  elif ! grep -q -- "$field" stderr; then
    fail "$name: error does not name $field: $(cat stderr)"
  elif [ "$(grep -c . stderr)" -ne 1 ]; then
    fail "$name: more than one line of error: $(cat stderr)"
  elif compgen -G "$work/$name.*" >/dev/null; then
    fail "$name: left a file behind"
  else
    pass
  fi
}

printf '[mesh]\nshape = "sphere"\n[light]\nposition = [0.1, 0.0, 0.0]\n' >inside.toml
printf '[medium]\neta = 1.5\n' >nomesh.toml
expect_error bad-method method "$scene" --method jensen
expect_error light-inside light.position inside.toml
expect_error no-mesh mesh nomesh.toml
printf '[mesh]\nshape = "sphere"\n[light]\nposition = [0, 0, 4]\n' >pointlight.toml
expect_error volumetric-point-light light.radius pointlight.toml --method volumetric
expect_error colour-single-scatter medium "$milk" --method holzschuch
printf '[mesh]\nshape = "sphere"\n[floor]\nheight = -2\n' >floor.toml
expect_error floor-single-scatter floor floor.toml --method walter
printf '[mesh]\nshape = "sphere"\n[floor]\nheight = 0.5\n' >highfloor.toml
expect_error floor-above floor.height highfloor.toml --method volumetric
printf '[mesh]\nshape = "sphere"\n[camera]\nposition = [0.2, 0.1, 0.0]\n' >camera.toml
expect_error camera-inside camera.position camera.toml --method volumetric
printf '[mesh]\nshape = "sphere"\n[light]\nposition = [0, 0, 4]\nradius = 0.2\n' >lit.toml
{ cat lit.toml; printf '[environment]\nradiance = 0.5\n'; } >environment.toml
{ cat lit.toml; printf '[environment]\nradiance = -0.5\n'; } >darker.toml
expect_error environment-single-scatter environment environment.toml --method walter
expect_error environment-negative environment.radiance darker.toml --method volumetric
expect_error missing-scene scene "$work/none.toml"
if "$exe" render "$scene" --width 4 --height 4 --out "$work/no/such/dir/x.exr" >stdout 2>stderr; then
  fail "bad-dir: exited 0"
elif ! grep -q "^scatterlab: error: --out:" stderr || [ "$(grep -c . stderr)" -ne 1 ]; then
  fail "bad-dir: $(cat stderr)"
else
  pass
fi

report render_runs
