#!/usr/bin/env bash
# Usage: units_runs.sh SCATTERLAB SOURCE_DIR
# Materials and physical length units from the command line: --material/--channel and
# [medium] material runs write files labelled in the table's unit (mm) with the material in
# /parameters; --length-unit with --sigma-t lets the searchlight run sigma_t != 1; mfp stays the
# default; every bad input is one error line naming the flag or key, exit status 2, no file.
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

small=(--photons 4000 --batches 4 --threads 2)

# expect_error COMMAND NAME FIELD ARGS...: exit 2, FIELD on the one line of stderr, no file.
expect_error() { expect_command_error "$@"; }

# A Narasimhan material, one channel: coefficients, grid and tallies in mm, the material recorded.
# (Espresso absorbs: few events per photon, so the run is quick under the sanitizers too.)
if "$exe" simulate --material espresso --channel red --tallies fluence --r-max 2 --z-min -1 \
  --z-max 4 "${small[@]}" --out "$work/espresso.h5" >"$work/stdout" 2>"$work/stderr"; then
  pass
  expect_info espresso "$work/espresso.h5" "length_unit +mm" "material +espresso" "channel +red" \
    "material_table +narasimhan2006" "sigma_s +0\.270(7|69)" "g +0\.907" \
    "r +[0-9]+ bins in \[0, 2\] mm" "z +[0-9]+ bins in \[-1, 4\] mm" \
    "fluence .*W mm\^-2 per W incident" "absorbed_mean_depth .*, mm$"
  if grep -q "material espresso (narasimhan2006), red channel" "$work/stdout"; then pass; else
    fail "espresso summary: $(cat "$work/stdout")"; fi
else
  fail "espresso run: $(cat "$work/stderr")"
fi

# Jensen's ketchup in a scene, swept over the three channels: one file per channel.
printf '[medium]\nmaterial = "ketchup"\nchannel = ["red", "green", "blue"]\n[tallies]\nradiance = false\n' \
  >"$work/ketchup.toml"
if "$exe" simulate --scene "$work/ketchup.toml" "${small[@]}" --out-dir "$work/ketchup" \
  >"$work/stdout" 2>"$work/stderr" && [ -f "$work/ketchup/channel=red.h5" ] &&
  [ -f "$work/ketchup/channel=blue.h5" ]; then
  pass
  expect_info ketchup_blue "$work/ketchup/channel=blue.h5" "channel +blue" "material +ketchup" \
    "material_note +.*similarity" "sigma_a +1\.45" "g +0$"
else
  fail "ketchup sweep: $(cat "$work/stderr")"
fi

# The searchlight with a material takes its eta (Jensen: 1.3) and runs with sigma_t != 1.
if "$exe" searchlight --material skin1 --channel green --r-max 5 --z-max 5 --r-bins 20 \
  --z-bins 10 "${small[@]}" --out "$work/skin.h5" >"$work/stdout" 2>"$work/stderr"; then
  pass
  expect_info skin "$work/skin.h5" "eta +1\.3$" "length_unit +mm" "r +20 bins in \[0, 5\] mm" \
    "reflectance .*W mm\^-2 per W incident"
else
  fail "skin searchlight: $(cat "$work/stderr")"
fi
# Coefficients in cm by flags; --eta overrides nothing here but is kept when given.
if "$exe" searchlight --length-unit cm --sigma-t 4 --albedo 0.9 --eta 1 --r-max 2.5 --z-max 2.5 \
  --r-bins 10 --z-bins 5 "${small[@]}" --out "$work/cm.h5" >/dev/null 2>"$work/stderr"; then
  pass
  expect_info cm "$work/cm.h5" "sigma_t +4$" "length_unit +cm" "r +10 bins in \[0, 2\.5\] cm" \
    "exitant_radiance .*W cm\^-2 sr\^-1 per W incident"
else
  fail "searchlight in cm: $(cat "$work/stderr")"
fi

# mfp stays the default, labelled as before.
if "$exe" simulate --tallies fluence "${small[@]}" --out "$work/mfp.h5" >/dev/null 2>&1; then
  expect_info mfp "$work/mfp.h5" "length_unit +mfp" "r +15 bins in \[0, 1\.5\] mfp" \
    "fluence .*W mfp\^-2 per W incident"
  if "$exe" info "$work/mfp.h5" | grep -q "material"; then fail "mfp file names a material"; else pass; fi
else
  fail "mfp run"
fi

if "$exe" simulate --help | grep -q -- "--material" && "$exe" searchlight --help | grep -q -- "--length-unit"
then pass; else fail "help lists --material and --length-unit"; fi

expect_error simulate unknown_material --material --material ketchp --channel red
if grep -q 'did you mean "ketchup"' "$work/stderr"; then pass; else fail "no did-you-mean: $(cat "$work/stderr")"; fi
expect_error simulate no_channel --channel --material apple
expect_error simulate bad_channel --channel --material apple --channel violet
expect_error simulate channel_without_material --channel --channel red
expect_error simulate material_with_albedo --albedo --material apple --channel red --albedo 0.5
expect_error searchlight material_with_sigma_t --sigma-t --material apple --channel red --sigma-t 2
expect_error simulate material_in_mfp --length-unit --material apple --channel red --length-unit mfp
expect_error simulate unknown_unit medium.length_unit --length-unit furlong
expect_error simulate sigma_t_in_mfp medium.length_unit --sigma-t 2
expect_error searchlight searchlight_sigma_t_in_mfp medium.length_unit --sigma-t 2
printf '[medium]\nmaterial = "wholemlk"\nchannel = "red"\n' >"$work/typo.toml"
expect_error simulate scene_unknown_material medium.material --scene "$work/typo.toml"
printf '[medium]\nmaterial = "wholemilk"\nchannel = "red"\nalbedo = 0.5\n' >"$work/mixed.toml"
expect_error searchlight scene_material_and_albedo medium.albedo --scene "$work/mixed.toml"

report units_runs
