#!/usr/bin/env bash
# Usage: layered_slab_runs.sh SCATTERLAB SOURCE_DIR
# The layered slab from the command line. simulate runs data/scenes/skin-slab.toml (and a layer
# of a measured material), and refuses the infinite medium's flags and bad slab scenes naming the
# key. scatterlab mcml: MCML's sample input runs, prints the energy balance and
# writes sample.h5 (the slab, its grid and MCML's tallies) in the current directory, and with
# --mco MCML's own .mco, whose sections a CONV-like reader finds in MCML's order; a file of two
# runs writes two files; a bad .mci, a bad flag or two runs with one output name are refused with
# one line naming the line and field, exit status 2, and nothing written.
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

sample=$source_dir/data/mcml/sample.mci
small=(--photons 20000 --batches 8 --threads 2)

if "$exe" mcml "$sample" --mco "${small[@]}" >"$work/stdout" 2>"$work/stderr"; then
  pass
  if grep -Eq "energy per W incident: specular_reflectance 0\.0243729 ± 0, diffuse_reflectance .*, total_transmittance .*, absorbed .* total 1\.000000" \
    "$work/stdout"; then pass; else fail "energy line: $(cat "$work/stdout")"; fi
  expect_info sample "$work/sample.h5" "geometry +slab" "length_unit +cm" "n_above +1$" \
    "weighting +analog" "r +50 bins in \[0, 0\.5\] cm" "z +40 bins in \[0, 0\.4\] cm" \
    "layer +3 bins in \[0, 0\.4\] cm" "specular_reflectance +scalar" \
    "diffuse_reflectance_by_radius +\[50\] \(r\), W cm\^-2 per W incident" \
    "total_transmittance_by_radius_angle +\[50 x 1\] \(r,theta_o\), W cm\^-2 sr\^-1" \
    "absorbed_by_radius_depth +\[50 x 40\] \(r,z\), W cm\^-3" "absorbed_by_layer +\[3\]" \
    "diffuse_reflectance_multiple"
  # MCML's sections, in MCML's order, each once.
  sections=$(grep -E "^(InParm|RAT|A_l|A_z|Rd_r|Rd_a|Tt_r|Tt_a|A_rz|Rd_ra|Tt_ra)\b" "$work/sample.mco" |
    awk '{print $1}' | tr '\n' ' ')
  if [ "$sections" = "InParm RAT A_l A_z Rd_r Rd_a Tt_r Tt_a A_rz Rd_ra Tt_ra " ]; then pass; else
    fail "sections of sample.mco: $sections"; fi
  if grep -q "^20000 " "$work/sample.mco"; then pass; else fail "sample.mco: photons not 20000"; fi
else
  fail "sample.mci: $(cat "$work/stderr")"
fi

# Two runs, two files; implicit capture is recorded.
cat >"$work/two.mci" <<'MCI'
1.0
2
one.mco A
1000
0.01 0.01
4 4 2
1
1
1.4 1 50 0.8 0.1
1
two.mco A
1000
0.01 0.01
4 4 2
2
1
1.4 1 50 0.8 0.05
1.4 0 0 0 0.05
1.33
MCI
if "$exe" mcml "$work/two.mci" --weighting implicit --batches 4 >"$work/stdout" 2>"$work/stderr"
then
  expect_info one "$work/one.h5" "weighting +implicit" "layer +1 bins"
  expect_info two "$work/two.h5" "n_below +1\.33" "layer +2 bins in \[0, 0\.1\] cm"
  if [ -e "$work/one.mco" ]; then fail "one.mco written without --mco"; else pass; fi
  # With --resume, runs whose files are complete are not run again.
  if "$exe" mcml "$work/two.mci" --weighting implicit --batches 4 --resume >"$work/stdout" \
    2>"$work/stderr" && [ "$(grep -c "^skip .*: done already" "$work/stdout")" -eq 2 ]; then
    pass
  else
    fail "--resume of a finished file: $(cat "$work/stdout" "$work/stderr")"
  fi
  expect_refused two_checkpoints --checkpoint mcml "$work/two.mci" --checkpoint "$work/c.ckpt"
  # --out names the file of a file of one run; several runs go to --out-dir, which must exist.
  expect_refused two_outs --out mcml "$work/two.mci" -o "$work/x.h5"
  expect_refused missing_dir --out-dir mcml "$work/two.mci" --out-dir "$work/none"
  mkdir "$work/runs"
  if "$exe" mcml "$work/two.mci" --batches 4 --out-dir "$work/runs" >"$work/stdout" 2>"$work/stderr" &&
    [ -s "$work/runs/one.h5" ] && [ -s "$work/runs/two.h5" ] &&
    grep -q "wrote $work/runs/two.h5" "$work/stdout"; then pass; else
    fail "--out-dir: $(cat "$work/stdout" "$work/stderr"; ls "$work/runs")"; fi
else
  fail "two.mci: $(cat "$work/stderr")"
fi
rm -f "$work"/*.h5 "$work"/*.mco
if "$exe" mcml "$sample" "${small[@]}" --mco -o "$work/named.h5" >"$work/stdout" 2>"$work/stderr" &&
  [ -s "$work/named.h5" ] && [ -s "$work/named.mco" ] && [ ! -e "$work/sample.h5" ]; then pass; else
  fail "mcml -o: $(cat "$work/stderr"; ls "$work")"; fi
rm -f "$work"/*.h5 "$work"/*.mco

# Refusals: one line naming the place, status 2, nothing written.
bad_mci() {
  local name=$1 field=$2 text=$3
  printf '%s\n' "$text" >"$scratch/$name.mci"
  expect_refused "$name" "$field" mcml "$scratch/$name.mci" --batches 4
}
bad_mci photons "4 photons" $'1.0\n1\nx.mco A\n1e6\n0.01 0.01\n4 4 2\n1\n1\n1.4 1 50 0.8 0.1\n1'
bad_mci g "layer 1 g" $'1.0\n1\nx.mco A\n1000\n0.01 0.01\n4 4 2\n1\n1\n1.4 1 50 1.0 0.1\n1'
bad_mci same_name "output file" $'1.0\n2\nx.mco A\n1000\n0.01 0.01\n4 4 2\n1\n1\n1.4 1 50 0.8 0.1\n1\nx.mco A\n1000\n0.01 0.01\n4 4 2\n1\n1\n1.4 1 50 0.8 0.1\n1'
expect_refused weighting --weighting mcml "$sample" --weighting russian
expect_refused missing "mcml input" mcml "$scratch/none.mci"
expect_refused batches run.batches mcml "$sample" --photons 10 --batches 64

# The shipped slab scene, and a layer of a measured material in mm behind a clear layer. Skin's
# photons take hundreds of events each: 2000 of them keep a run to seconds under the sanitizers.
small=(--photons 2000 --batches 8 --threads 2)
if "$exe" simulate --scene "$source_dir/data/scenes/skin-slab.toml" "${small[@]}" \
  --out "$work/skin.h5" >"$work/stdout" 2>"$work/stderr"; then
  if grep -Eq "energy per W incident: specular_reflectance 0\.0277778 ± 0, .* total 1\.000000" \
    "$work/stdout"; then pass; else fail "skin energy line: $(cat "$work/stdout")"; fi
  expect_info skin "$work/skin.h5" "geometry +slab" "layer +3 bins in \[0, 0\.71\] cm" \
    "r +200 bins in \[0, 2\] cm" "weighting +analog"
else
  fail "skin-slab.toml: $(cat "$work/stderr")"
fi
cat >"$work/marble.toml" <<'TOML'
[geometry]
type = "slab"
length_unit = "mm"
[[layers]]
mu_a = 0
mu_s = 0
g = 0
n = 1.5
thickness = 1
[[layers]]
material = "marble"
channel = "red"
thickness = inf
[run]
weighting = "implicit"
TOML
if "$exe" simulate "$work/marble.toml" "${small[@]}" --out "$work/marble.h5" >"$work/stdout" \
  2>"$work/stderr"; then
  expect_info marble "$work/marble.h5" "length_unit +mm" "weighting +implicit" \
    "layer +2 bins in \[0, inf\] mm" "absorbed_by_radius_depth .*W mm\^-3"
else
  fail "marble: $(cat "$work/stderr")"
fi

# Two seeds of a slab merge, with its layers; a slab of other layers is refused, naming them.
sed 's/mu_s = 187.0/mu_s = 188.0/' "$source_dir/data/scenes/skin-slab.toml" >"$work/other.toml"
if "$exe" simulate --scene "$source_dir/data/scenes/skin-slab.toml" "${small[@]}" --seed 2 \
  --out "$work/skin2.h5" >/dev/null 2>"$work/stderr" &&
  "$exe" simulate --scene "$work/other.toml" "${small[@]}" --seed 3 --out "$work/other.h5" \
    >/dev/null 2>>"$work/stderr" &&
  "$exe" merge "$work/skin.h5" "$work/skin2.h5" --out "$work/merged.h5" >/dev/null \
    2>>"$work/stderr"; then
  expect_info merged "$work/merged.h5" "geometry +slab" "merged from"
  expect_refused other_layers parameters.layers.mu_s merge "$work/skin.h5" "$work/other.h5" \
    --out "$work/mixed.h5"
else
  fail "slab runs to merge: $(cat "$work/stderr")"
fi

# The infinite medium's flags are not the slab's; bad scenes name their key.
small=(--photons 1000 --batches 4)
scene=$source_dir/data/scenes/skin-slab.toml
expect_command_error simulate albedo --albedo "$scene" --albedo 0.5
expect_command_error simulate r_bins --r-bins "$scene" --r-bins 10
bad() {
  local name=$1 field=$2 text=$3
  printf '%s\n' "$text" >"$work/$name.toml"
  expect_command_error simulate "$name" "$field" "$work/$name.toml"
}
layer=$'[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0.8\nn = 1.4\nthickness = 0.1'
bad no_layers layers $'[geometry]\ntype = "slab"'
bad no_g 'layers\[1\].g' $'[geometry]\ntype = "slab"\n[[layers]]\nmu_a = 1\nmu_s = 10\nn = 1.4\nthickness = 0.1'
bad typo 'layers\[2\].mu_ss' $'[geometry]\ntype = "slab"\n'"$layer"$'\n[[layers]]\nmu_ss = 1'
bad middle_inf 'layers\[1\].thickness' $'[geometry]\ntype = "slab"\n[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0.8\nn = 1.4\nthickness = inf\n'"$layer"
bad mixed 'layers\[1\].mu_a' $'[geometry]\ntype = "slab"\n[[layers]]\nmaterial = "marble"\nchannel = "red"\nmu_a = 1\nthickness = 1'
bad n_above geometry.n_above $'[geometry]\ntype = "slab"\nn_above = 0\n'"$layer"
bad weighting run.weighting $'[geometry]\ntype = "slab"\n'"$layer"$'\n[run]\nweighting = "russian"'
bad unit geometry.length_unit $'[geometry]\ntype = "slab"\nlength_unit = "inch"\n'"$layer"
# Flags lay over the scene before it is checked as a whole: a flag can complete a scene that
# is incomplete alone (10 photons cannot fill the default 64 batches; 4 can).
printf '%s\n' '[geometry]' 'type = "slab"' "$layer" '[run]' 'photons = 10' >"$work/few.toml"
small=(--threads 1)
expect_command_error simulate few run.batches "$work/few.toml"
if "$exe" simulate "$work/few.toml" --batches 4 --out "$work/few.h5" >"$work/stdout" 2>&1 &&
  [ -s "$work/few.h5" ]; then pass; else fail "few photons mended by --batches: $(cat "$work/stdout")"; fi

report layered_slab_runs
