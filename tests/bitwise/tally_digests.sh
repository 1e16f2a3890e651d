#!/usr/bin/env bash
# Runs a fixed set of scenes that covers every transport kernel: every geometry (the infinite
# medium, the half-space, the analytic sphere, a convex and a non-convex mesh, the layered slab),
# every light of each (beam, point, directional, pole beam, off-axis beam, sphere of light), both
# phase functions, both estimators with each source, split orders, normal and oblique incidence,
# eta = 1, eta > 1 and eta < 1, a finite escape radius, analog and implicit weighting, and prints
# every tally's digest. The scenes of the sphere, the meshes and the slab are in scenes/.
#
#   tally_digests.sh SCATTERLAB TALLY_DIGEST              prints "<scene> <tally> <digest>"
#   tally_digests.sh SCATTERLAB TALLY_DIGEST --check FILE  compares with FILE, exit 1 on a change
#
# tally_digests.txt beside this script holds the digests of the kernels as they stood before
# the transport engine was unified (the first 13 scenes), and of the scenes added after them as
# they stood when added (CHANGELOG.md); a refactor that should not change results must keep them.
# The isotropic scenes' (beam_isotropic, point_collision, half_space_fresnel,
# half_space_matched_oblique, half_space_conservative) are those of the walk that draws a
# direction afresh at g = 0 instead of rotating the old one: the same law, other bits. The flux
# and absorbed_mean_depth of the collision-estimator infinite-medium scenes are those of the lane
# walk (transport/lane_walk.hpp): the same paths, whose sums of direction cosines and depths
# differ in the last bits (at most 8.3e-15 of the largest cell); the counts are the same.
set -euo pipefail
scatterlab=$1 digest=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {  # run NAME ARGS...: one scene
  local name=$1
  shift
  "$scatterlab" "$@" --photons 20000 --batches 8 --seed 7 --threads 2 --out "$work/$name.h5" \
    >/dev/null
  "$digest" "$work/$name.h5" | sed "s/^/$name /"
}

scenes=$(dirname "$0")/scenes

all() {
  run beam_collision simulate
  run beam_track_length simulate --estimator track_length
  run beam_collision_orders simulate --split-orders
  run beam_track_length_orders_folded simulate --estimator track_length --split-orders --fold-phi
  run beam_isotropic simulate --g 0 --albedo 0.9 --estimator track_length
  run beam_conservative simulate --albedo 1 --g 0.5 --escape-radius 4
  run point_collision simulate --source point --g 0 --albedo 0.8 --split-orders
  run point_track_length simulate --source point --g 0.3 --estimator track_length
  run half_space_fresnel searchlight
  run half_space_matched_oblique searchlight --eta 1 --incidence 60 --albedo 0.9
  run half_space_hg_oblique searchlight --eta 1.4 --incidence 45 --g 0.8 --no-fluence
  run half_space_low_index searchlight --eta 0.8 --incidence 30 --g -0.3
  run half_space_conservative searchlight --albedo 1 --escape-radius 6
  run beam_collision_isotropic simulate --g 0 --albedo 0.7
  run point_collision_hg simulate --source point --g 0.7 --albedo 0.9
  run point_track_length_isotropic simulate --source point --g 0 --albedo 0.9 \
    --estimator track_length --split-orders
  for scene in sphere_directional sphere_pole_beam_matched sphere_beam_off_axis \
    mesh_bumpy_directional mesh_box_beam mesh_sphere_light_matched slab_analog slab_implicit; do
    run "$scene" simulate "$scenes/$scene.toml"
  done
}

if [ "${3:-}" = "--check" ]; then
  all >"$work/now.txt"
  if diff -u "$4" "$work/now.txt"; then
    echo "bitwise: $(wc -l <"$4") tallies in $(cut -d' ' -f1 "$4" | uniq | wc -l) scenes are the same, bit for bit"
  else
    echo "bitwise: tallies differ from $4 (lines above: - reference, + now)"
    exit 1
  fi
else
  all
fi
