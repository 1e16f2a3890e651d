#!/usr/bin/env bash
# Usage: data_loss.sh SCATTERLAB SOURCE_DIR
# No command destroys a file it did not create for itself: an output that is an input, another
# output, a device, a FIFO, a directory or someone else's file at the checkpoint path is refused
# (exit 2, the flag named) before any work, and every file that was there is byte for byte the
# same afterwards, with no file added. Paths with control characters or over the filesystem's
# limits are refused the same way. An interrupted run does not replace a complete file, and the
# temporaries a killed run left are removed by the next.
set -u
exe=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

# The files a careless user has lying about.
"$exe" simulate "${tiny[@]}" "${grid[@]}" --seed 1 --out a.h5 >/dev/null || fail "setup: a.h5"
"$exe" simulate "${tiny[@]}" "${grid[@]}" --seed 2 --out b.h5 >/dev/null || fail "setup: b.h5"
cp "$source_dir/data/scenes/paper-beam.toml" scene.toml
cp "$source_dir/data/scenes/searchlight.toml" half.toml
write_tet_render_scene "$source_dir" 4
echo "my notes" >notes.txt
mkfifo fifo
mkdir dir
ln a.h5 a-hard.h5
ln -s a.h5 a-soft.h5
# The device through a link: a command that wrongly renames onto it replaces the link, never the
# system's /dev/null.
ln -s /dev/null device

# --- outputs that are inputs or other outputs --------------------------------------------------
expect_refused "simulate: checkpoint is the output" --checkpoint \
  simulate "${tiny[@]}" --out a.h5 --checkpoint a.h5
expect_refused "simulate: checkpoint is the new output, spelled otherwise" --checkpoint \
  simulate "${tiny[@]}" --out new.h5 --checkpoint ./dir/../new.h5
expect_refused "simulate: checkpoint is someone's notes" --checkpoint \
  simulate "${tiny[@]}" --out new.h5 --checkpoint notes.txt
expect_refused "simulate: checkpoint is another simulation" --checkpoint \
  simulate "${tiny[@]}" --out new.h5 --checkpoint b.h5
expect_refused "simulate: output is the scene" --out \
  simulate --scene scene.toml "${tiny[@]}" --out scene.toml
expect_refused "simulate: checkpoint is the scene" --checkpoint \
  simulate --scene scene.toml "${tiny[@]}" --out new.h5 --checkpoint scene.toml
expect_refused "simulate: output is the scene, spelled otherwise" --out \
  simulate --scene "$(pwd)/scene.toml" "${tiny[@]}" --out ./dir/../scene.toml
expect_refused "searchlight: checkpoint is the output" --checkpoint \
  searchlight "${tiny[@]}" --out a.h5 --checkpoint a-hard.h5
expect_refused "searchlight: output is the scene" --out \
  searchlight --scene half.toml "${tiny[@]}" --out half.toml
expect_refused "fit: CSV is the simulation" --csv fit a.h5 --csv a.h5
expect_refused "fit: CSV is the simulation, spelled otherwise" --csv fit a.h5 --csv ./dir/../a.h5
expect_refused "fit: CSV is a hard link to the simulation" --csv fit a.h5 --csv a-hard.h5
expect_refused "fit: CSV is a symlink to the simulation" --csv fit a.h5 --csv a-soft.h5
expect_refused "merge: output is an input" --out merge a.h5 b.h5 -o a.h5
expect_refused "merge: output is the second input" --out merge a.h5 b.h5 -o ./b.h5
expect_refused "merge: output is a link to an input" --out merge a.h5 b.h5 -o a-soft.h5
expect_refused "render: output is the scene" --out render render.toml --out render.toml
expect_refused "render: output is the mesh" --out render render.toml --out tet.obj

# --- outputs that are not files -----------------------------------------------------------------
expect_refused "simulate: output is a device" --out simulate "${tiny[@]}" --out device
expect_refused "simulate: output is a FIFO" --out simulate "${tiny[@]}" --out fifo
expect_refused "simulate: output is a directory" --out simulate "${tiny[@]}" --out dir
expect_refused "simulate: checkpoint is a FIFO" --checkpoint \
  simulate "${tiny[@]}" --out new.h5 --checkpoint fifo
expect_refused "simulate: checkpoint is a directory" --checkpoint \
  simulate "${tiny[@]}" --out new.h5 --checkpoint dir
expect_refused "simulate: --out-dir is a file" --out-dir \
  simulate "${tiny[@]}" --out-dir notes.txt
expect_refused "searchlight: output is a FIFO" --out searchlight "${tiny[@]}" --out fifo
expect_refused "fit: CSV is a device" --csv fit a.h5 --csv device
expect_refused "fit: CSV is a directory" --csv fit a.h5 --csv dir
expect_refused "merge: output is a FIFO" --out merge a.h5 b.h5 -o fifo
expect_refused "render: output is a directory" --out render render.toml --out dir
expect_refused "render --study: output is a file" --out render --study --quick --out notes.txt
expect_refused "report: output is a file" --out report --quick --out notes.txt
expect_refused "validate deon: output is a file" --out validate deon --quick --out notes.txt
expect_refused "validate searchlight: output is a file" --out \
  validate searchlight --quick --out notes.txt

# --- directories of someone else's files: a command that names its own files there never writes
# into one (a re-run of its own directory is fine) ------------------------------------------------
mkdir -p theirs
echo "my report" >theirs/report.md
printf '[medium]\nalbedo = [0.3, 0.6]\n' >sweep.toml
expect_refused "report into a directory of other files" --out \
  report --quick --section refractive_solver --out theirs
expect_refused "validate deon into a directory of other files" --out \
  validate deon --quick --out theirs
expect_refused "validate searchlight into a directory of other files" --out \
  validate searchlight --quick --out theirs
expect_refused "render --study into a directory of other files" --out \
  render --study --quick --out theirs
expect_refused "a sweep into a directory of other files" --out \
  simulate sweep.toml "${tiny[@]}" --out theirs
expect_refused "--out-dir: a directory of other files" --out-dir \
  simulate "${tiny[@]}" --out-dir theirs
# Its own directory, marked on the first run, takes the second run's files.
if "$exe" report --quick --section refractive_solver --threads 1 --out own >/dev/null &&
  [ -f own/.scatterlab-outputs ] &&
  "$exe" report --quick --section refractive_solver --threads 1 --out own >/dev/null; then pass
else fail "report re-run into its own directory: $(ls -A own 2>&1)"; fi
rm -rf own

# --- paths no filesystem should be given -------------------------------------------------------
long_name=$(printf 'n%.0s' $(seq 300)).h5
deep_path=$(printf 'd/%.0s' $(seq 2100))x.h5
expect_refused "simulate: tab in the output" --out simulate "${tiny[@]}" --out "$(printf 'a\tb.h5')"
expect_refused "simulate: newline in the output" --out \
  simulate "${tiny[@]}" --out "$(printf 'a\nb.h5')"
expect_refused "simulate: escape in the checkpoint" --checkpoint \
  simulate "${tiny[@]}" --out new.h5 --checkpoint "$(printf 'c\033[2J.h5')"
expect_refused "simulate: name over NAME_MAX" --out simulate "${tiny[@]}" --out "$long_name"
expect_refused "simulate: path over PATH_MAX" --out simulate "${tiny[@]}" --out "$deep_path"
expect_refused "simulate: --out-dir name over NAME_MAX" --out-dir \
  simulate "${tiny[@]}" --out-dir "$long_name"
expect_refused "fit: control character in the CSV" --csv fit a.h5 --csv "$(printf 'f\x01.csv')"
expect_refused "merge: name over NAME_MAX" --out merge a.h5 b.h5 -o "$long_name"
expect_refused "report: control character in the directory" --out \
  report --quick --out "$(printf 'r\x7f')"
printf '[output]\npath = "o\\u0000.h5"\n' >nul.toml
expect_refused "simulate: NUL byte in the scene's output path" output.path \
  simulate --scene nul.toml "${tiny[@]}"

# --- what a run may remove: only its own checkpoint ----------------------------------------------
if "$exe" simulate "${tiny[@]}" "${grid[@]}" --out own.h5 --checkpoint own.ckpt \
  --checkpoint-interval 1b >/dev/null 2>&1 && [ -f own.h5 ] && [ ! -e own.ckpt ]; then pass; else
  fail "own checkpoint: not removed at the end of the run ($(ls))"
fi
if [ "$(cat notes.txt)" = "my notes" ]; then pass; else fail "notes.txt changed"; fi

# --- temporaries left by a killed run: removed by the next, those of a live process kept ---------
echo partial >a.h5.tmp-2147483646-0
echo partial >own.h5.checkpoint.tmp-2147483646-3
echo live >a.h5.tmp-$$-0
if "$exe" simulate "${tiny[@]}" "${grid[@]}" --seed 1 --out a.h5 >/dev/null 2>stale.err &&
  [ ! -e a.h5.tmp-2147483646-0 ] && grep -q "removed .*a.h5.tmp-2147483646-0" stale.err &&
  [ -e a.h5.tmp-$$-0 ]; then pass; else fail "stale output temporary: $(cat stale.err; ls)"; fi
if "$exe" simulate "${tiny[@]}" "${grid[@]}" --out own.h5 >/dev/null 2>stale.err &&
  [ ! -e own.h5.checkpoint.tmp-2147483646-3 ] && grep -q "own.h5.checkpoint.tmp" stale.err
then pass; else fail "stale checkpoint temporary: $(cat stale.err; ls)"; fi
rm -f a.h5.tmp-$$-0

# --- SIGINT beside a complete file: the file stays, the partial result goes beside it -----------
wait_for() { for _ in $(seq 1000); do [ -e "$1" ] && return 0; sleep 0.02; done; return 1; }
long=(simulate --photons 6000000 --batches 48 --threads 2 --seed 11 --theta-bins 6 --phi-bins 8)
# A complete file of other parameters (fewer photons) at the name the interrupted run writes.
"$exe" "${long[@]}" --photons 48000 --out done.h5 >/dev/null || fail "setup: done.h5"
sha_before=$(sha256sum done.h5)
"$exe" "${long[@]}" --out done.h5 --checkpoint-interval 4b >/dev/null 2>stopped.err &
pid=$!
if wait_for done.h5.checkpoint; then
  kill -INT $pid
  wait $pid
  status=$?
  if [ $status -eq 130 ] && [ "$(sha256sum done.h5)" = "$sha_before" ] &&
    "$exe" info done.partial.h5 | grep -q PARTIAL && grep -q "done.partial.h5" stopped.err; then
    pass
  else
    fail "SIGINT beside a complete file: exit $status, $(cat stopped.err; ls)"
  fi
  if "$exe" "${long[@]}" --out done.h5 --resume >/dev/null 2>&1 &&
    ! "$exe" info done.h5 | grep -q PARTIAL && [ ! -e done.partial.h5 ] &&
    [ ! -e done.h5.checkpoint ]; then pass; else fail "resume after SIGINT: $(ls)"; fi
else
  kill -KILL $pid 2>/dev/null
  fail "no checkpoint written"
fi

report data_loss
