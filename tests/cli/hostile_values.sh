#!/usr/bin/env bash
# Usage: hostile_values.sh SCATTERLAB SOURCE_DIR
# Values no command may take silently, each refused with one error naming the flag or
# key and what is accepted, exit status 2, no hang, and every file that was there byte for byte
# the same afterwards, with none added:
#   threads beyond what the machine can honour (--threads, OMP_NUM_THREADS, run.threads),
#   empty and malformed numbers (CLI11 read '' as 0, -1 as 2^64 - 1 and 010 as 8),
#   grids whose bins underflow or overflow (NaN or inf tallies), an index that makes NaN,
#   seeds outside [0, 2^63 - 1] on the command line and in scene files,
#   scene files that are not small regular files (/dev/urandom, FIFOs, directories, > 1 MiB),
#   flags that contradict each other.
# And the edges of the accepted ranges run and write finite tallies.
set -u
exe=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

# The files lying about, which must come out untouched.
"$exe" simulate "${tiny[@]}" "${grid[@]}" --out a.h5 >/dev/null || fail "setup: a.h5"
cp "$source_dir/data/scenes/paper-beam.toml" scene.toml
cp "$source_dir/data/scenes/searchlight.toml" half.toml
write_tet_render_scene "$source_dir" 4
echo "my notes" >notes.txt
mkfifo fifo
mkdir dir
head -c 1100000 /dev/zero | tr '\0' '#' >big.toml  # a comment over 1 MiB
printf '[run]\nthreads = 100000\n' >threads.toml
printf '[run]\nseed = -1\n' >seed.toml
printf '[surface]\neta = 1.3\n[tallies]\nfluence = false\n' >nofluence.toml

# --- 1. threads: at most 4 per hardware thread, from every flag, OMP_NUM_THREADS and scenes -----
expect_refused "simulate --threads 100000" --threads simulate "${tiny[@]}" --threads 100000 --out t.h5
expect_refused "simulate --threads -1" --threads simulate "${tiny[@]}" --threads -1 --out t.h5
expect_refused "searchlight --threads 100000" --threads \
  searchlight "${tiny[@]}" --threads 100000 --out t.h5
expect_refused "fit --threads 100000" --threads fit a.h5 --models sg --threads 100000
expect_refused "render --threads 100000" --threads render render.toml --threads 100000 --out t.exr
expect_refused "render --study --threads 100000" --threads \
  render --study --quick --threads 100000 --out study
expect_refused "validate deon --threads 100000" --threads \
  validate deon --quick --threads 100000 --out vd
expect_refused "validate searchlight --threads 100000" --threads \
  validate searchlight --quick --threads 100000 --out vs
expect_refused "report --threads 100000" --threads report --quick --threads 100000 --out rep
expect_refused "scene run.threads = 100000" run.threads \
  simulate --scene threads.toml --photons 2000 --batches 4 --out t.h5
ENV_SET="OMP_NUM_THREADS=100000" expect_refused "simulate, OMP_NUM_THREADS=100000" \
  OMP_NUM_THREADS simulate --photons 2000 --batches 4 --out t.h5
ENV_SET="OMP_NUM_THREADS=100000" expect_refused "searchlight --threads 0, OMP_NUM_THREADS=100000" \
  OMP_NUM_THREADS searchlight --photons 2000 --batches 4 --threads 0 --out t.h5
ENV_SET="OMP_NUM_THREADS=100000" expect_refused "fit, OMP_NUM_THREADS=100000" \
  OMP_NUM_THREADS fit a.h5 --models sg
ENV_SET="OMP_NUM_THREADS=100000" expect_refused "render, OMP_NUM_THREADS=100000" \
  OMP_NUM_THREADS render render.toml --out t.exr
# The bound is in the error and in --help.
"$exe" simulate "${tiny[@]}" --threads 100000 --out t.h5 2>"$scratch/err" >/dev/null
if grep -q "accepted: an integer in \[0, [1-9][0-9]*\]" "$scratch/err"; then pass; else
  fail "threads: no range in the error: $(cat "$scratch/err")"; fi
for command in simulate searchlight fit render report "validate deon" "validate searchlight"; do
  # shellcheck disable=SC2086
  if "$exe" $command --help | grep -q "at most 4 per hardware thread"; then pass; else
    fail "$command --help does not give the bound of --threads"; fi
done
# Within the bound it runs (more threads than batches is fine).
if "$exe" simulate --photons 2000 --batches 4 --threads 4 "${grid[@]}" --out threads4.h5 \
  >/dev/null 2>"$scratch/err" && [ -f threads4.h5 ]; then pass; else
  fail "simulate --threads 4: $(cat "$scratch/err")"; fi
rm -f threads4.h5

# --- 2. empty and malformed numbers: never a silent 0 ---------------------------------------------
expect_refused "simulate --albedo ''" --albedo simulate "${tiny[@]}" --albedo '' --out t.h5
expect_refused "simulate --albedo=" --albedo simulate "${tiny[@]}" --albedo= --out t.h5
expect_refused "simulate --photons ''" --photons simulate --photons '' --batches 4 --out t.h5
expect_refused "simulate --batches ''" --batches simulate --photons 2000 --batches '' --out t.h5
expect_refused "simulate --r-bins ''" --r-bins simulate "${tiny[@]}" --r-bins '' --out t.h5
expect_refused "simulate --albedo nan" --albedo simulate "${tiny[@]}" --albedo nan --out t.h5
expect_refused "simulate --albedo 0.5x" --albedo simulate "${tiny[@]}" --albedo 0.5x --out t.h5
expect_refused "simulate --r-max 1e999" --r-max simulate "${tiny[@]}" --r-max 1e999 --out t.h5
expect_refused "simulate --r-bins 010" --r-bins simulate "${tiny[@]}" --r-bins 010 --out t.h5
expect_refused "simulate --r-bins 0x10" --r-bins simulate "${tiny[@]}" --r-bins 0x10 --out t.h5
expect_refused "simulate --batches -1" --batches simulate --photons 2000 --batches -1 --out t.h5
expect_refused "searchlight --eta ''" --eta searchlight "${tiny[@]}" --eta '' --out t.h5
expect_refused "searchlight --incidence ''" --incidence \
  searchlight "${tiny[@]}" --incidence '' --out t.h5
expect_refused "fit --quadrature ''" --quadrature fit a.h5 --models sg --quadrature ''
expect_refused "render --width ''" --width render render.toml --width '' --out t.exr
expect_refused "render --gamma ''" --gamma render render.toml --gamma '' --out t.exr
expect_refused "validate deon --photons ''" --photons validate deon --photons '' --out vd
expect_refused "validate searchlight --albedo ''" --albedo \
  validate searchlight --quick --albedo '' --out vs
expect_refused "report --seed ''" --seed report --quick --seed '' --out rep
expect_refused "invert --eta ''" --eta invert --Rd 0.5 --ld 1 --eta ''

# --- 3. values that would make NaN or inf tallies -------------------------------------------------
expect_refused "simulate --r-max 1e-300" grid.r.max simulate "${tiny[@]}" --r-max 1e-300 --out t.h5
expect_refused "simulate --r-max 1e300" grid.r.max simulate "${tiny[@]}" --r-max 1e300 --out t.h5
expect_refused "simulate --z-min -1e308 --z-max 1e308" grid.z.min \
  simulate "${tiny[@]}" --z-min -1e308 --z-max 1e308 --out t.h5
expect_refused "simulate --rho-max 1e-200" grid.rho.max \
  simulate "${tiny[@]}" --source point --tallies fluence_spherical --rho-max 1e-200 --out t.h5
expect_refused "simulate, sigma_t 1e-20 / mm" grid.r.max \
  simulate "${tiny[@]}" --length-unit mm --sigma-t 1e-20 --out t.h5
expect_refused "simulate, escape radius beyond a double in mfp" run.escape_radius \
  simulate "${tiny[@]}" --length-unit mm --sigma-t 1e10 --albedo 1 --escape-radius 1e300 --out t.h5
expect_refused "searchlight --r-max 1e-300" grid.r.max \
  searchlight "${tiny[@]}" --r-max 1e-300 --out t.h5
expect_refused "searchlight --z-max 1e300" grid.z.max \
  searchlight "${tiny[@]}" --z-max 1e300 --out t.h5
expect_refused "searchlight --eta 1e-300" surface.eta searchlight "${tiny[@]}" --eta 1e-300 --out t.h5
expect_refused "searchlight --eta 1e300" surface.eta searchlight "${tiny[@]}" --eta 1e300 --out t.h5
# The edges of what is accepted run, and write only finite numbers.
finite_run() {
  local name=$1
  shift
  if "$exe" "$@" --out edge.h5 >/dev/null 2>"$scratch/err" && "$exe" info edge.h5 >"$scratch/info" &&
    ! grep -qi "nan\|inf " "$scratch/info"; then pass; else
    fail "$name: $(cat "$scratch/err" "$scratch/info" 2>/dev/null | head -5)"
  fi
  rm -f edge.h5
}
finite_run "simulate, bins 1e-12 mfp wide" simulate "${tiny[@]}" "${grid[@]}" --r-max 4e-12
finite_run "simulate, z over +-1e12 mfp" simulate "${tiny[@]}" "${grid[@]}" --z-min -1e12 --z-max 1e12
finite_run "searchlight, r and z at the edges" searchlight "${tiny[@]}" --r-bins 4 --z-bins 4 \
  --r-max 4e-12 --z-max 1e12
finite_run "searchlight, eta 0.1 at grazing incidence" searchlight "${tiny[@]}" --r-bins 4 \
  --z-bins 4 --eta 0.1 --incidence 89.9
finite_run "searchlight, eta 10 at grazing incidence" searchlight "${tiny[@]}" --r-bins 4 \
  --z-bins 4 --eta 10 --incidence 89.9

# --- 4. seeds: [0, 2^63 - 1] on the command line and in scene files, one check -------------------
expect_refused "simulate --seed -1" --seed simulate "${tiny[@]}" --seed -1 --out t.h5
expect_refused "simulate --seed 2^63" --seed simulate "${tiny[@]}" --seed 9223372036854775808 --out t.h5
expect_refused "simulate --seed 2^64" --seed simulate "${tiny[@]}" --seed 18446744073709551616 --out t.h5
if grep -q "18446744073709551616" "$scratch/stderr"; then pass; else
  fail "seed 2^64 read as another number: $(cat "$scratch/stderr")"; fi
expect_refused "simulate --seed ''" --seed simulate "${tiny[@]}" --seed '' --out t.h5
expect_refused "searchlight --seed 2^63" --seed \
  searchlight "${tiny[@]}" --seed 9223372036854775808 --out t.h5
expect_refused "render --seed 2^63" --seed render render.toml --seed 9223372036854775808 --out t.exr
expect_refused "validate deon --seed 2^63" --seed \
  validate deon --quick --seed 9223372036854775808 --out vd
expect_refused "validate deon --seed 2^63 - 1 (7 seeds from it)" --seed \
  validate deon --quick --seed 9223372036854775807 --out vd
expect_refused "report --seed 2^63 - 1 (seeds from it upward)" --seed \
  report --quick --seed 9223372036854775807 --out rep
expect_refused "report --seed -1" --seed report --quick --seed -1 --out rep
expect_refused "scene run.seed = -1" run.seed simulate --scene seed.toml "${tiny[@]}" --out t.h5
# The same range, in the same words, from the flag and from the key.
"$exe" simulate "${tiny[@]}" --seed 9223372036854775808 --out t.h5 2>"$scratch/flag" >/dev/null
"$exe" simulate --scene seed.toml "${tiny[@]}" --out t.h5 2>"$scratch/key" >/dev/null
if grep -q "accepted: an integer in \[0, 2^63 - 1\]" "$scratch/flag" &&
  grep -q "accepted: an integer in \[0, 2^63 - 1\]" "$scratch/key"; then pass; else
  fail "seed ranges differ: $(cat "$scratch/flag" "$scratch/key")"; fi
if "$exe" simulate "${tiny[@]}" "${grid[@]}" --seed 9223372036854775807 --out top.h5 >/dev/null \
  2>"$scratch/err"; then pass; else fail "seed 2^63 - 1: $(cat "$scratch/err")"; fi
rm -f top.h5 t.h5

# --- 5. scene files: regular files of at most 1 MiB, never opened otherwise -----------------------
expect_refused "simulate --scene /dev/urandom" --scene simulate --scene /dev/urandom --out t.h5
expect_refused "simulate --scene FIFO" --scene simulate --scene fifo --out t.h5
expect_refused "simulate --scene directory" --scene simulate --scene dir --out t.h5
expect_refused "simulate --scene over 1 MiB" --scene simulate --scene big.toml --out t.h5
expect_refused "simulate --scene missing" --scene simulate --scene none.toml --out t.h5
expect_refused "searchlight --scene FIFO" --scene searchlight --scene fifo --out t.h5
expect_refused "searchlight --scene /dev/zero" --scene searchlight --scene /dev/zero --out t.h5
expect_refused "render FIFO" scene render fifo --out t.exr
expect_refused "render /dev/urandom" scene render /dev/urandom --out t.exr
expect_refused "render --study FIFO" scene render --study --quick fifo --out study
if "$exe" simulate --help | grep -q "at most 1 MiB"; then pass; else fail "--scene help: no limit"; fi

# --- 6. flags that contradict each other -----------------------------------------------------------
expect_refused "searchlight --no-fluence --model-fluence" --model-fluence \
  searchlight "${tiny[@]}" --no-fluence --model-fluence --out t.h5
expect_refused "searchlight --model-fluence, scene without fluence" --model-fluence \
  searchlight --scene nofluence.toml "${tiny[@]}" --model-fluence --out t.h5
expect_refused "simulate --out with --out-dir" --out-dir \
  simulate "${tiny[@]}" --out t.h5 --out-dir outdir
expect_refused "validate deon --quick --photons" --quick validate deon --quick --photons 1e5 --out vd
expect_refused "validate searchlight --quick --photons" --quick \
  validate searchlight --quick --photons 1e5 --out vs
expect_refused "render --study --method" --method render --study --quick --method walter --out study
expect_refused "render --study --width" --width render --study --quick --width 8 --out study

# --- 7. render: meshes that enclose nothing, sizes outside their ranges, names of another format ---
# mesh_scene NAME OBJ_TEXT: a render scene of the tile's settings on the mesh in NAME.obj.
mesh_scene() {
  printf '%b' "$2" >"$1.obj"
  sed -e "s/tet.obj/$1.obj/" render.toml >"$1.toml"
}
tet_faces='f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n'
mesh_scene nanvertex "v 0 0 0\nv nan 0 0\nv 0 1 0\nv 0 0 1\n$tet_faces"
mesh_scene infvertex "v 0 0 0\nv 1 0 0\nv 0 inf 0\nv 0 0 1\n$tet_faces"
mesh_scene flat "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n$tet_faces"
mesh_scene insideout "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n"
mesh_scene sliver "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0.5 0.5 0\n\
f 1 3 5\nf 1 5 2\nf 2 5 3\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
rm -f t.exr t.png
expect_refused "render: a NaN vertex" mesh render nanvertex.toml --out t.exr
expect_refused "render: an infinite vertex" mesh render infvertex.toml --out t.exr
expect_refused "render: a flat (zero-volume) mesh" mesh render flat.toml --out t.exr
expect_refused "render: an inside-out mesh" mesh render insideout.toml --out t.exr
expect_refused "render: a zero-area triangle" mesh render sliver.toml --out t.exr
expect_refused "render --width 0" --width render render.toml --width 0 --out t.exr
expect_refused "render --width 16385" --width render render.toml --width 16385 --out t.exr
expect_refused "render --height -3" --height render render.toml --height -3 --out t.exr
expect_refused "render --samples 2^20 + 1" --samples render render.toml --samples 1048577 --out t.exr
expect_refused "render --light-samples 4097" --light-samples \
  render render.toml --light-samples 4097 --out t.exr
expect_refused "render --light-samples 0" --light-samples \
  render render.toml --light-samples 0 --out t.exr
sed -e 's/^width = .*/width = 20000/' render.toml >wide.toml
expect_refused "render: image.width = 20000" image.width render wide.toml --out t.exr
sed -e 's/^light_samples = .*/light_samples = 5000/' render.toml >lights.toml
expect_refused "render: image.light_samples = 5000" image.light_samples render lights.toml --out t.exr
sed -e 's/^\[mesh\]$/[mesh]\nshape = "bumpy_sphere"\nfrequency = 65/' -e '/^shape = "obj"/d' \
  -e '/^path = /d' render.toml >bumpy.toml
expect_refused "render: mesh.frequency = 65" mesh.frequency render bumpy.toml --out t.exr
sed -e 's/^\[mesh\]$/[mesh]\nshape = "sphere"\nrings = 5000/' -e '/^shape = "obj"/d' \
  -e '/^path = /d' render.toml >rings.toml
expect_refused "render: mesh.rings = 5000" mesh.rings render rings.toml --out t.exr
# Every size in its range, their product months of work: refused before any pixel, as simulate
# refuses more than 2^53 events.
expect_refused "render: 16384^2 pixels x 2^20 samples" image.samples \
  render render.toml --width 16384 --height 16384 --samples 1048576 --out t.exr
expect_refused "render pathtrace: 16384^2 pixels x 2^20 samples" image.width \
  render render.toml --method pathtrace --width 16384 --height 16384 --samples 1048576 --out t.exr
expect_refused "render --out x.png" --out render render.toml --out x.png
expect_refused "render --out x (no extension)" --out render render.toml --out x

if [ "$(cat notes.txt)" = "my notes" ]; then pass; else fail "notes.txt changed"; fi
report hostile_values
