#!/usr/bin/env bash
# Usage: command_line.sh SCATTERLAB SOURCE_DIR SAME_TALLIES
# One command line across commands:
#   every --help shows each default the one way CLI11 does (--albedo FLOAT=0.5), taken from the
#   built-in defaults, with no typed "[default]" and no "{true}" artefacts;
#   a mistyped flag or command is refused as a bad value is (exit 2, one line, nothing written)
#   and names the nearest accepted spelling;
#   a scene is --scene FILE or a positional FILE in every command that reads one;
#   searchlight chooses its tallies with --tallies, as simulate does;
#   --out names a directory where a command writes many files, made when missing;
#   fit, report and explore run in their components' programs.
set -u
exe=$(realpath "$1")
source_dir=$(realpath "$2")
same_tallies=$(realpath "$3")
source "$(dirname "$0")/harness.sh"

# --- 1. defaults in --help -----------------------------------------------------------------------
commands=(simulate searchlight fit render report "validate deon" "validate searchlight"
  "validate litsphere" merge
  info invert)
for command in "${commands[@]}"; do
  # shellcheck disable=SC2086 # "validate deon" is two words
  "$exe" $command --help >"$scratch/help" 2>&1 || fail "$command --help: exit status $?"
  # A typed default closed an option's description in brackets ("[0.5]", "[radiance,fluence]",
  # "[mfp; a material's table unit]"); a range ("[0, 1]") has a comma and a space.
  if grep -E '^  -.*\[([^],]|,[^ ])*\]$' "$scratch/help" >"$scratch/typed"; then
    fail "$command --help types a default into the text: $(cat "$scratch/typed")"
  elif grep -q '{true}\|{false}\|=\[\]' "$scratch/help"; then
    fail "$command --help shows an artefact: $(grep '{true}\|{false}\|=\[\]' "$scratch/help")"
  else
    pass
  fi
done
# The defaults shown are the ones a run without flags uses (transport/simulation.hpp,
# transport/searchlight.hpp, transport/run_settings.hpp).
expect_default() {
  local command=$1 shown=$2
  # shellcheck disable=SC2086
  if "$exe" $command --help | grep -q -- "^  $shown "; then pass; else
    fail "$command --help does not show $shown"
  fi
}
expect_default simulate "--albedo FLOAT=0.5"
expect_default simulate "--g FLOAT=0.9"
expect_default simulate "--photons FLOAT=1e+08"
expect_default simulate "--batches UINT=64"
expect_default simulate "--seed UINT=1"
expect_default simulate "--escape-radius FLOAT=inf"
expect_default simulate "--r-bins INT=15"
expect_default simulate "--z-min FLOAT=-1"
expect_default simulate "-o,--out TEXT=scatterlab.h5"
# One spelling for the file or directory a command writes: -o, --out.
for command in simulate searchlight mcml merge report render "validate deon" "validate searchlight" \
  "validate litsphere"; do
  # shellcheck disable=SC2086
  if "$exe" $command --help | grep -q -- "^  -o,--out "; then pass; else
    fail "$command --help has no -o,--out"
  fi
done
expect_default searchlight "--albedo FLOAT=0.99"
expect_default searchlight "--photons FLOAT=1e+07"
expect_default searchlight "--eta FLOAT=1.3"
expect_default searchlight "--r-bins INT=200"
expect_default searchlight "--tallies TEXT=fluence"
expect_default fit "--quadrature INT=3"
expect_default "validate deon" "--photons FLOAT=1e+06"
# The file of a run without medium flags holds the medium the help shows.
"$exe" simulate "${tiny[@]}" "${grid[@]}" --out defaults.h5 >/dev/null || fail "defaults run"
if "$exe" info defaults.h5 | grep -q '^  albedo  *0.5$' &&
  "$exe" info defaults.h5 | grep -q '^  g  *0.9$'; then pass; else
  fail "the default run's medium is not the help's: $("$exe" info defaults.h5 | grep -E 'albedo|  g ')"
fi

# --- 2. mistyped flags and commands --------------------------------------------------------------
expect_suggestion() {
  local name=$1 suggestion=$2
  shift 2
  expect_refused "$name" "did you mean $suggestion?" "$@"
}
expect_suggestion "simulate --albdo" --albedo simulate "${tiny[@]}" --albdo 0.3 --out t.h5
expect_suggestion "simulate --albdo=0.3" --albedo simulate "${tiny[@]}" --albdo=0.3 --out t.h5
expect_suggestion "simulate --photon" --photons simulate --photon 2000 --out t.h5
expect_suggestion "searchlight --etta" --eta searchlight "${tiny[@]}" --etta 1.4 --out t.h5
expect_suggestion "searchlight --talies" --tallies searchlight "${tiny[@]}" --talies none --out t.h5
expect_suggestion "fit --model" --models fit defaults.h5 --model sg
expect_suggestion "render --widht" --width render --widht 4 --out t.exr
expect_suggestion "report --secton" --section report --secton lobe_fits --out rep
expect_suggestion "validate deon --quik" --quick validate deon --quik --out deon
expect_suggestion "invert --modle" --model invert --Rd 0.5 --ld 1 --modle dipole
expect_suggestion "merge --outt" --out merge defaults.h5 defaults.h5 --outt m.h5
expect_suggestion "simulte" simulate simulte "${tiny[@]}"
expect_suggestion "validate serchlight" searchlight validate serchlight --quick
# Nothing near: still one line and status 2, without a guess.
expect_refused "simulate --zzz" "not a flag of simulate" simulate "${tiny[@]}" --zzz --out t.h5
if grep -q "did you mean" "$scratch/stderr"; then fail "--zzz got a guess: $(cat "$scratch/stderr")"
else pass; fi

# --- 3. the scene: --scene FILE or FILE --------------------------------------------------------
cp "$source_dir/data/scenes/paper-beam.toml" beam.toml
cp "$source_dir/data/scenes/searchlight.toml" half.toml
for command in simulate searchlight; do
  scene=beam.toml
  [ "$command" = searchlight ] && scene=half.toml
  "$exe" "$command" --scene "$scene" "${tiny[@]}" --r-bins 4 --out "$command-flag.h5" >/dev/null &&
    "$exe" "$command" "$scene" "${tiny[@]}" --r-bins 4 --out "$command-positional.h5" >/dev/null ||
    fail "$command with a scene: exit status $?"
  if "$same_tallies" "$command-flag.h5" "$command-positional.h5" >"$scratch/same"; then pass; else
    fail "$command: --scene and a positional scene differ: $(cat "$scratch/same")"
  fi
done
# Both at once would be a silent choice of one.
expect_refused "simulate with two scenes" "--scene" simulate beam.toml --scene beam.toml \
  "${tiny[@]}" --out t.h5
sed -e 's/^width = .*/width = 4/' -e 's/^height = .*/height = 4/' -e 's/^samples = .*/samples = 1/' \
  "$source_dir/data/scenes/tile.toml" >tile.toml
if "$exe" render --scene tile.toml --threads 1 --out tile.exr >/dev/null && [ -s tile.png ]; then
  pass
else fail "render --scene tile.toml"; fi

# --- 4. searchlight --tallies -------------------------------------------------------------------
"$exe" searchlight "${tiny[@]}" --r-bins 4 --tallies none --out no-fluence.h5 >/dev/null ||
  fail "searchlight --tallies none"
"$exe" searchlight "${tiny[@]}" --r-bins 4 --no-fluence --out alias.h5 >/dev/null ||
  fail "searchlight --no-fluence"
if ! "$exe" info no-fluence.h5 | grep -q '^ *fluence ' &&
  "$exe" info searchlight-flag.h5 | grep -q '^ *fluence '; then pass; else
  fail "--tallies none kept the fluence, or the default run has none"
fi
if "$same_tallies" no-fluence.h5 alias.h5 >"$scratch/same"; then pass; else
  fail "--no-fluence and --tallies none differ: $(cat "$scratch/same")"
fi
expect_refused "searchlight --tallies radiance" --tallies searchlight "${tiny[@]}" \
  --tallies radiance --out t.h5
expect_refused "searchlight --tallies none --model-fluence" --model-fluence searchlight \
  "${tiny[@]}" --tallies none --model-fluence --out t.h5
expect_refused "searchlight --tallies with --no-fluence" --no-fluence searchlight "${tiny[@]}" \
  --tallies fluence --no-fluence --out t.h5
expect_refused "simulate --tallies none" tallies simulate "${tiny[@]}" --tallies none --out t.h5

# --- 5. --out for many files: a directory, made when missing ------------------------------------
printf '[medium]\nalbedo = [0.3, 0.6]\n' >sweep.toml
if "$exe" simulate sweep.toml "${tiny[@]}" "${grid[@]}" --out new/sweep >/dev/null &&
  [ -f "new/sweep/albedo=0.3.h5" ] && [ -f "new/sweep/albedo=0.6.h5" ]; then pass; else
  fail "simulate sweep --out new/sweep: $(ls -R new 2>&1)"
fi
expect_refused "simulate sweep without --out" --out simulate sweep.toml "${tiny[@]}"
# validate and report take minutes in the unoptimised sanitizer build (a minute for validate
# searchlight --quick, 3 for one report section); the Release suite runs them.
if ldd "$exe" | grep -q libasan; then
  echo "note: AddressSanitizer build: the validate and report directories are left to Release"
else
  if "$exe" validate searchlight --quick --threads 1 --out deep/a/b >/dev/null &&
    [ -n "$(ls deep/a/b/*.csv 2>/dev/null)" ]; then pass; else
    fail "validate searchlight --out deep/a/b: $(ls -R deep 2>&1)"
  fi
  if "$exe" report --quick --section refractive_solver --threads 1 --out deep/c/d >/dev/null &&
    [ -f deep/c/d/report.md ]; then pass; else
    fail "report --out deep/c/d: $(ls -R deep 2>&1)"
  fi
fi

# --- 6. the components' programs -----------------------------------------------------------------
# fit, report and explore run in programs of their own beside scatterlab, so that a run of photons
# loads none of Ceres's, the HTTP server's or their TLS libraries; without its program beside it,
# the command is one line and exit status 1, and writes nothing.
if ldd "$exe" | grep -E "libglog|libcholmod|libcpp-httplib|libmuparser|libssl|libcurl" \
  >"$scratch/loaded"; then
  fail "scatterlab loads a component's libraries: $(cat "$scratch/loaded")"
else
  pass
fi
mkdir -p alone && cp "$exe" alone/scatterlab
status=0
alone/scatterlab fit defaults.h5 --out alone/fits.h5 >"$scratch/stdout" 2>"$scratch/stderr" ||
  status=$?
if [ "$status" -eq 1 ] && [ "$(grep -c . "$scratch/stderr")" -eq 1 ] &&
  grep -q "fit: its program scatterlab-fit is not beside" "$scratch/stderr" &&
  [ ! -e alone/fits.h5 ]; then
  pass
else
  fail "fit without scatterlab-fit beside: status $status, $(cat "$scratch/stderr")"
fi

report command_line
