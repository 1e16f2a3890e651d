#!/usr/bin/env bash
# Usage: cli_end_to_end.sh SCATTERLAB SOURCE_DIR
# A small run writes a readable file; every bad input gets one clear error naming the field, a
# non-zero exit and no output file (nor a temporary one).
set -u
exe=$1
source_dir=$2
source "$source_dir/tests/cli/harness.sh"

expect_error() { expect_command_error simulate "$@"; }
expect_searchlight_error() { expect_command_error searchlight "$@"; }

# A small run, then info on it.
if "$exe" simulate --photons 20000 --batches 8 --out "$work/run.h5" >"$work/stdout" 2>"$work/stderr" &&
  grep -q "wrote $work/run.h5" "$work/stdout" && [ -f "$work/run.h5" ]; then pass; else
  fail "small run: $(cat "$work/stdout" "$work/stderr")"
fi
if "$exe" info "$work/run.h5" >"$work/info" && grep -q "radiance" "$work/info" &&
  grep -q "absorbed_outside_grid" "$work/info"; then pass; else fail "info: $(cat "$work/info")"; fi
if "$exe" simulate --scene "$source_dir/data/scenes/point-source.toml" --photons 20000 \
  --out "$work/point.h5" >/dev/null 2>&1 && "$exe" info "$work/point.h5" | grep -q fluence_spherical
then pass; else fail "point-source scene"; fi
if "$exe" simulate --help | grep -q -- "--albedo"; then pass; else fail "help"; fi

# fit on the small run: fits in the file, a CSV, a summary; a re-run replaces them. (The models
# the summary compares; all of them take minutes in an unoptimised sanitizer build.)
if "$exe" fit "$work/run.h5" --models sg,dexp,adexp --threads 2 >"$work/fit" 2>&1 &&
  grep -q "dexp beats sg" "$work/fit" &&
  grep -q "adexp beats sg and dexp" "$work/fit" && grep -q "fits/s" "$work/fit" &&
  [ -f "$work/run-fits.csv" ] && [ "$(wc -l <"$work/run-fits.csv")" -eq 601 ]; then pass; else
  fail "fit: $(cat "$work/fit")"
fi
if "$exe" fit "$work/run.h5" --models sg --csv "$work/two.csv" >"$work/fit" 2>&1 &&
  head -1 "$work/two.csv" | grep -q "^r_index,z_index,r,z,sg_status" && ! grep -qi nan "$work/two.csv" &&
  ! compgen -G "$work/run.h5.tmp*" >/dev/null; then pass; else fail "fit re-run: $(cat "$work/fit")"; fi
if "$exe" fit "$work/run.h5" --models sg,glow >/dev/null 2>"$work/stderr"; then fail "fit glow: exited 0"
elif grep -q "models" "$work/stderr" && [ "$(grep -c . "$work/stderr")" -eq 1 ]; then pass
else fail "fit glow: $(cat "$work/stderr")"; fi
if "$exe" simulate --photons 2000 --batches 4 --tallies fluence --out "$work/noradiance.h5" >/dev/null 2>&1 &&
  ! "$exe" fit "$work/noradiance.h5" 2>"$work/stderr" >/dev/null && grep -q "radiance" "$work/stderr"
then pass; else fail "fit without radiance: $(cat "$work/stderr")"; fi

expect_error albedo_above_one medium.albedo --albedo 1.5
expect_error g_at_one medium.g --g 1
expect_error g_below_minus_one medium.g --g -1.2
expect_error negative_sigma medium.sigma_t --sigma-t -2 --albedo 0.5
expect_error zero_photons run.photons --photons 0
expect_error fractional_photons run.photons --photons 2.5
expect_error one_batch run.batches --batches 1
expect_error r_max_zero grid.r.max --r-max 0
expect_error albedo_one_without_escape run.escape_radius --albedo 1
expect_error odd_phi_bins grid.phi.bins --phi-bins 7
expect_error unknown_tally --tallies --tallies fluence,glow
expect_error missing_directory out --out "$work/no/such/dir/x.h5" --photons 10
printf '[medium]\nalbdo = 0.3\n' >"$work/typo.toml"
expect_error unknown_key medium.albdo --scene "$work/typo.toml"
printf '[medium]\nsigma_a = -0.1\nsigma_s = 1\n' >"$work/negative.toml"
expect_error negative_coefficient medium.sigma_a --scene "$work/negative.toml"
printf '[medium\nalbedo = 0.3\n' >"$work/syntax.toml"
expect_error syntax_error "syntax.toml:" --scene "$work/syntax.toml"

# searchlight: a small half-space run, info on it, and bad input.
if "$exe" searchlight --photons 20000 --batches 8 --eta 1.33 --out "$work/half.h5" >"$work/stdout" 2>"$work/stderr" &&
  grep -q "wrote $work/half.h5" "$work/stdout" && grep -q "specular_reflectance" "$work/stdout" &&
  grep -q "^  single_scatter  *diffuse_reflectance_single" "$work/stdout" &&
  grep -q "^  better_dipole  *diffuse_reflectance_multiple" "$work/stdout" &&
  grep -q "^  quantized_diffusion  *diffuse_reflectance_multiple" "$work/stdout" &&
  grep -q "^  scatterlab_grosjean_beam  *diffuse_reflectance " "$work/stdout"; then pass; else
  fail "searchlight run: $(cat "$work/stdout" "$work/stderr")"
fi
if "$exe" info "$work/half.h5" >"$work/info" && grep -q "eta *1.33" "$work/info" &&
  grep -q "geometry *half_space" "$work/info" && grep -q "reflectance_single" "$work/info" &&
  grep -q "theta_o" "$work/info" && grep -q "^  single_scatter  *reflectance_single" "$work/info"
then pass; else fail "info on searchlight: $(cat "$work/info")"; fi
if "$exe" searchlight --eta 1 --albedo 0.9 --photons 20000 --batches 8 --no-fluence \
  --out "$work/matched.h5" | grep -q "exact diffuse reflectance"; then pass; else fail "index-matched summary"; fi
if "$exe" searchlight --help | grep -q -- "--incidence"; then pass; else fail "searchlight help"; fi
# Oblique incidence: the models say why they are absent, in the summary and in the file.
if "$exe" searchlight --incidence 30 --photons 20000 --batches 8 --no-fluence \
  --out "$work/oblique.h5" >"$work/stdout" &&
  grep -q "better_dipole .*normal incidence only" "$work/stdout" &&
  "$exe" info "$work/oblique.h5" | grep -q "better_dipole .*normal incidence only"; then pass; else
  fail "oblique models: $(cat "$work/stdout")"
fi

"$exe" report --quick --section half_space_modles --out "$work/no_report" >"$work/stdout" 2>"$work/stderr"
if [ $? -eq 2 ] && grep -q -- "--section" "$work/stderr" && grep -q "half_space_models" "$work/stderr" &&
  [ ! -e "$work/no_report" ]; then pass; else fail "report bad section: $(cat "$work/stderr")"; fi

# invert: (R_dr, l_d) -> (sigma_a, sigma_s) and the forward model back, per channel.
if "$exe" invert --Rd 0.5 0.3 0.2 --ld 2 1 0.5 --model better_dipole --length-unit cm \
    >"$work/stdout" &&
  awk '$1 == "red" && $7 == "0.5" && $8 == "2" {ok++} $1 == "green" && $7 == "0.3" && $8 == "1" {ok++}
       $1 == "blue" && $7 == "0.2" && $8 == "0.5" {ok++} /sigma_a \/cm/ {ok++}
       END {exit ok != 4}' "$work/stdout"; then pass; else fail "invert round trip: $(cat "$work/stdout")"; fi
for args in "--Rd 0.5 0.3 --ld 2 1:--Rd" "--Rd 0.5 --ld 2 --length-unit inch:--length-unit"; do
  "$exe" invert ${args%%:*} >"$work/stdout" 2>"$work/stderr"
  if [ $? -eq 2 ] && grep -q -- "${args##*:}" "$work/stderr" && [ "$(grep -c . "$work/stderr")" -eq 1 ]
  then pass; else fail "invert ${args%%:*}: $(cat "$work/stderr")"; fi
done
"$exe" invert --Rd 1.5 --ld 2 >"$work/stdout" 2>"$work/stderr"
if [ $? -eq 2 ] && grep -q "R_dr" "$work/stderr"; then pass; else fail "invert bad R_dr: $(cat "$work/stderr")"; fi
"$exe" invert --Rd 0.5 --ld 2 --model grosjean >"$work/stdout" 2>"$work/stderr"
if [ $? -eq 2 ] && grep -q -- "--model" "$work/stderr" && grep -q "quantized_diffusion" "$work/stderr"; then
  pass; else fail "invert bad model: $(cat "$work/stderr")"; fi

if "$exe" searchlight --scene "$source_dir/data/scenes/searchlight.toml" --photons 20000 --batches 8 \
  --out "$work/scene.h5" >/dev/null 2>&1 && "$exe" info "$work/scene.h5" | grep -q "eta *1.3"
then pass; else fail "searchlight scene"; fi
# Flags lay over the scene before it is checked as a whole: a scene that is incomplete or out of
# range alone is refused, naming the key, and runs once a flag completes or mends it.
printf '[medium]\nalbedo = 1\n' >"$work/conservative.toml"
expect_command_error searchlight scene_needs_radius run.escape_radius \
  --scene "$work/conservative.toml"
expect_command_error simulate scene_needs_radius_infinite run.escape_radius \
  --scene "$work/conservative.toml"
printf '[medium]\nalbedo = 1.5\n' >"$work/bad-albedo.toml"
expect_command_error simulate bad_key_alone medium.albedo --scene "$work/bad-albedo.toml"
mend=(--photons 2000 --batches 4 --threads 1)
if "$exe" searchlight --scene "$work/conservative.toml" --escape-radius 5 "${mend[@]}" \
  --no-fluence --out "$work/mended-half.h5" >/dev/null 2>&1 &&
  "$exe" simulate --scene "$work/conservative.toml" --escape-radius 5 "${mend[@]}" \
    --out "$work/mended.h5" >/dev/null 2>&1 &&
  "$exe" simulate --scene "$work/bad-albedo.toml" --albedo 0.5 "${mend[@]}" \
    --out "$work/mended-albedo.h5" >/dev/null 2>&1 &&
  "$exe" info "$work/mended-albedo.h5" | grep -q "albedo *0.5"
then pass; else fail "flags that mend a scene"; fi
# A scene read strictly: a misspelt key or a wrong type is refused, whatever the flags.
printf '[medium]\nalbdo = 0.5\n' >"$work/typo.toml"
expect_command_error simulate flag_over_typo medium.albdo --scene "$work/typo.toml" --albedo 0.5
printf '[medium]\nalbedo = "half"\n' >"$work/type.toml"
expect_command_error simulate flag_over_type medium.albedo --scene "$work/type.toml" --albedo 0.5
# A valid file, and flags over it: validated again after them.
printf '[medium]\nalbedo = 1\n[run]\nescape_radius = 5\n' >"$work/conservative.toml"
if "$exe" searchlight --scene "$work/conservative.toml" --escape-radius 4 --photons 2000 --batches 4 \
  --no-fluence --out "$work/conservative-half.h5" >/dev/null 2>&1 &&
  "$exe" simulate --scene "$work/conservative.toml" --photons 2000 --batches 4 \
    --out "$work/conservative.h5" >/dev/null 2>&1; then pass; else fail "complete scene"; fi
expect_command_error simulate flag_breaks_scene "escape.radius" \
  --scene "$work/conservative.toml" --escape-radius 0
printf '[surface]\nindx = 1.3\n' >"$work/half-typo.toml"
expect_searchlight_error searchlight_unknown_key surface.indx --scene "$work/half-typo.toml"
expect_searchlight_error eta_zero surface.eta --eta 0
expect_searchlight_error eta_negative surface.eta --eta -1.3
expect_searchlight_error grazing source.incidence_deg --incidence 90
expect_searchlight_error albedo_above_one medium.albedo --albedo 1.01
expect_searchlight_error g_at_minus_one medium.g --g -1
expect_searchlight_error conservative_without_escape run.escape_radius --albedo 1
expect_searchlight_error r_bins_zero grid.r.bins --r-bins 0
expect_searchlight_error searchlight_missing_directory out --out "$work/no/such/dir/x.h5"

# validate searchlight --quick: each model against the Monte Carlo part it models, once-scattered
# against the exact solver; every CSV and PNG written (4 pencil plots for the multiply-scattered
# part and 4 for all, 2 fluence plots, the once-scattered plot).
if "$exe" validate searchlight --quick --threads 2 --out "$work/half" >"$work/stdout" 2>"$work/stderr" &&
  grep -q "once scattered: exact total" "$work/stdout" &&
  grep -q "^  quantized_diffusion  *multiple" "$work/stdout" &&
  grep -q "^  better_dipole+single_scatter  *all" "$work/stdout" &&
  [ -s "$work/half/searchlight_single_scatter.csv" ] && [ -s "$work/half/searchlight_fluence.csv" ] &&
  [ "$(ls "$work"/half/*.png | wc -l)" -eq 11 ]; then pass; else
  fail "validate searchlight: $(cat "$work/stdout" "$work/stderr"; ls "$work/half")"
fi

# info on something that is not a scatterlab file.
echo "not hdf5" >"$work/text.h5"
if "$exe" info "$work/text.h5" >/dev/null 2>"$work/stderr"; then fail "info on text: exited 0"
elif grep -q "not a scatterlab HDF5 file" "$work/stderr"; then pass; else fail "info on text: $(cat "$work/stderr")"; fi

# validate deon --quick: the error table, both CSV files and every PNG (valid signature).
if "$exe" validate deon --quick --threads 2 --out "$work/deon" >"$work/stdout" 2>"$work/stderr" &&
  grep -q "Grosjean" "$work/stdout" && [ -s "$work/deon/deon_point_source.csv" ] &&
  [ "$(grep -c "^0.5,grosjean" "$work/deon/deon_errors.csv")" -eq 1 ]; then pass; else
  fail "validate deon: $(cat "$work/stdout" "$work/stderr")"
fi
pngs=0
for albedo in 0.01 0.1 0.3 0.5 0.7 0.9 0.99; do
  for scale in linear log; do
    f="$work/deon/deon_albedo_${albedo}_${scale}.png"
    [ "$(head -c 4 "$f" 2>/dev/null | tail -c 3)" = "PNG" ] && pngs=$((pngs + 1))
  done
done
f="$work/deon/deon_all_albedos_log.png"  # the overview of every albedo
[ "$(head -c 4 "$f" 2>/dev/null | tail -c 3)" = "PNG" ] && pngs=$((pngs + 1))
if [ "$pngs" -eq 15 ]; then pass; else fail "validate deon: $pngs of 15 PNG files"; fi
if compgen -G "$work/deon/*.tmp-*" >/dev/null; then fail "validate deon left temporary files"; else pass; fi
# Without python3 and matplotlib, the commands that draw figures stop before their work, say what
# to install, and write nothing.
if SCATTERLAB_PYTHON="$work/no-python3" "$exe" validate deon --quick --out "$work/deon-nopy" \
  >/dev/null 2>"$work/stderr"; then
  fail "validate deon without python3: exited 0"
elif grep -q "figures need python3 with matplotlib (Debian: python3-matplotlib)" "$work/stderr" &&
  [ ! -e "$work/deon-nopy" ]; then pass; else
  fail "validate deon without python3: $(cat "$work/stderr"; ls "$work/deon-nopy" 2>&1)"
fi
if "$exe" validate deon --photons 2.5 --out "$work/deon2" >/dev/null 2>"$work/stderr"; then
  fail "validate deon --photons 2.5: exited 0"
elif grep -q "photons" "$work/stderr" && [ ! -e "$work/deon2" ]; then pass; else
  fail "validate deon --photons 2.5: $(cat "$work/stderr")"
fi

report cli
