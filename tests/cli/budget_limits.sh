#!/usr/bin/env bash
# Usage: budget_limits.sh SCATTERLAB SOURCE_DIR
# Memory and time known before a run starts. Each refused with one error naming the fields that
# drive it and what is accepted, exit status 2, within a minute, before anything is allocated or
# written, and every file that was there byte for byte the same afterwards:
#   grids within every per-axis limit whose tallies are far over the machine's memory, and runs
#   over --memory-limit (simulate, searchlight, sweeps, render, and the files info, merge and fit
#   read), and --memory-limit values that are not sizes;
#   files whose datasets declare more than the file holds (8 TB in a few kB);
#   photon counts past 2^53, albedo 1 with an escape radius of 1e30 mfp and albedos so near 1 that
#   the run would take years, sweeps of millions of points; a run of a quarter of an hour says so
#   before it starts.
# And a run within the limit still runs; an allocation that fails anyway is one line, exit 1.
set -u
exe=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/harness.sh"

# The files lying about, which must come out untouched.
"$exe" simulate "${tiny[@]}" "${grid[@]}" --out a.h5 >/dev/null || fail "setup: a.h5"
"$exe" simulate "${tiny[@]}" "${grid[@]}" --seed 2 --out b.h5 >/dev/null || fail "setup: b.h5"
write_tet_render_scene "$source_dir" 4
sed -e 's/^light_samples = .*/light_samples = 1000000000/' render.toml >lights.toml
grep -q '^light_samples = 1000000000' lights.toml || fail "setup: lights.toml has no light_samples"
echo "my notes" >notes.txt

# --- 1. memory: estimated from the tally declarations before the first buffer ------------------
# 1e5 x 1e5 bins are within every axis limit; the fluence alone is 80 GB per array.
expect_refused "simulate, fluence of 1e10 cells" "grid.r.bins x grid.z.bins" \
  simulate "${tiny[@]}" --tallies fluence --r-bins 100000 --z-bins 100000 --out t.h5
expect_refused "simulate, the figure is in the error" "GiB for" \
  simulate "${tiny[@]}" --tallies fluence --r-bins 100000 --z-bins 100000 --out t.h5
expect_refused "simulate, radiance over --memory-limit 64M" \
  "grid.r.bins x grid.z.bins x grid.theta.bins x grid.phi.bins" \
  simulate "${tiny[@]}" --r-bins 100 --z-bins 100 --memory-limit 64M --out t.h5
expect_refused "simulate, split by order over --memory-limit 16M" \
  "tallies.split_by_order" \
  simulate "${tiny[@]}" --r-bins 30 --split-orders --memory-limit 16M --out t.h5
expect_refused "simulate, a buffer per thread" "run.threads" \
  simulate --photons 2000 --batches 8 --threads 8 --r-bins 30 --memory-limit 64M --out t.h5
expect_refused "searchlight, fluence of 1e10 cells" "grid.r.bins x grid.z.bins" \
  searchlight "${tiny[@]}" --r-bins 100000 --z-bins 100000 --out t.h5
expect_refused "searchlight over --memory-limit 1M" "grid.r.bins x grid.z.bins" \
  searchlight "${tiny[@]}" --memory-limit 1M --out t.h5
expect_refused "simulate --resume over --memory-limit leaves a.h5" "grid" \
  simulate "${tiny[@]}" --r-bins 30 --resume --memory-limit 16M --out a.h5
printf '[grid.r]\nbins = [4, 100000]\n[grid.z]\nbins = 100000\n[tallies]\nradiance = false\n' \
  >sweep-memory.toml
expect_refused "a sweep with one point over memory runs none of them" \
  "grid.r.bins x grid.z.bins" \
  simulate --scene sweep-memory.toml "${tiny[@]}" --out-dir sweep-memory
expect_refused "render, a billion light tables" "image.light_samples" \
  render lights.toml --out t.exr
expect_refused "render, 16384 x 16384 pixels over --memory-limit 1G" \
  "image.width x image.height" \
  render render.toml --width 16384 --height 16384 --memory-limit 1G --out t.exr

# --- 2. --memory-limit: a size, on every command that runs work or reads files ------------------
for bad in '' 0 -1 12X 1e3 4GiBs 99999999999T; do
  expect_refused "--memory-limit '$bad'" --memory-limit \
    simulate "${tiny[@]}" --memory-limit "$bad" --out t.h5
done
for command in "searchlight --out t.h5" "info a.h5" "fit a.h5 --models sg" \
  "merge a.h5 b.h5 --out t.h5" "render render.toml --out t.exr" "report --quick --out rep" \
  "validate deon --quick --out vd" "validate searchlight --quick --out vs"; do
  read -r -a words <<<"$command"
  expect_refused "$command --memory-limit x" --memory-limit \
    "${words[@]}" --memory-limit x
done

# --- 3. files read: the declared shape is checked before the values are allocated ---------------
expect_refused "info over --memory-limit 1K names file and dataset" \
  "a.h5:/tallies/radiance/mean" info a.h5 --memory-limit 1K
expect_refused "merge over --memory-limit 1K" "a.h5:/tallies/radiance/mean" \
  merge a.h5 b.h5 --out t.h5 --memory-limit 1K
expect_refused "fit over --memory-limit 1K" "a.h5:/tallies/radiance" \
  fit a.h5 --models sg --memory-limit 1K
# info holds a tally's mean, stderr and their ratios at once: 3 x 3.0 MiB for the default grid's
# radiance (388800 values), so 6M, which each dataset alone fits, is refused and 10M is not.
"$exe" simulate "${tiny[@]}" --out default-grid.h5 >/dev/null || fail "setup: default-grid.h5"
expect_refused "info: mean, stderr and ratios over --memory-limit 6M" \
  "mean, stderr and their ratios" info default-grid.h5 --memory-limit 6M
if "$exe" info default-grid.h5 --memory-limit 10M >/dev/null; then pass; else
  fail "info default-grid.h5 --memory-limit 10M"; fi
if /usr/bin/python3 -c 'import h5py' 2>/dev/null; then
  # a.h5 with its radiance replaced by one that declares 1e6 x 1e6 doubles, one chunk stored.
  cp a.h5 crafted.h5
  /usr/bin/python3 - <<'PY'
import h5py
with h5py.File("crafted.h5", "r+") as f:
    del f["tallies/radiance/mean"]
    d = f["tallies/radiance"].create_dataset("mean", shape=(1000000, 1000000), dtype="f8",
                                             chunks=(64, 64))
    d[0, 0] = 1.0
    # The stderr alike, along dimensions of no grid axis, so that the shapes agree with the
    # tally's dims and the declared size is what is refused.
    del f["tallies/radiance/stderr"]
    f["tallies/radiance"].create_dataset("stderr", shape=(1000000, 1000000), dtype="f8",
                                         chunks=(64, 64))
    f["tallies/radiance"].attrs["dims"] = "a,b"
PY
  size=$(stat -c %s crafted.h5)
  if [ "$size" -gt 1000000 ]; then fail "setup: crafted.h5 is $size bytes"; fi
  timeout -k 10 60 "$exe" info crafted.h5 >"$scratch/stdout" 2>"$scratch/stderr"
  status=$?
  if [ $status -ne 2 ]; then
    fail "info of an 8 TB declared dataset: exit $status: $(cat "$scratch/stderr")"
  elif ! grep -q "crafted.h5:/tallies/radiance/mean" "$scratch/stderr" ||
    ! grep -q "1000000 x 1000000" "$scratch/stderr"; then
    fail "info of an 8 TB declared dataset: file, dataset or shape not named: $(cat "$scratch/stderr")"
  else
    pass
  fi
  expect_refused "merge of an 8 TB declared dataset" "crafted.h5" \
    merge a.h5 crafted.h5 --out t.h5
else
  echo "note: no h5py for /usr/bin/python3; the crafted-file cases are in the unit tests only"
fi

# --- 4. runs that would never finish ---------------------------------------------------------
expect_refused "simulate --photons 2^63" run.photons \
  simulate --photons 9223372036854775808 --batches 4 --out t.h5
expect_refused "simulate --photons 2^53 + 2" run.photons \
  simulate --photons 9007199254740994 --batches 4 --albedo 0 --out t.h5
expect_refused "albedo 1, escape radius 1e30" "medium.albedo, run.escape_radius" \
  simulate "${tiny[@]}" --albedo 1 --escape-radius 1e30 --out t.h5
expect_refused "searchlight albedo 1, escape radius 1e30" \
  "medium.albedo, run.escape_radius" \
  searchlight "${tiny[@]}" --albedo 1 --escape-radius 1e30 --out t.h5
expect_refused "albedo 1 - 1e-10, 1e8 photons" run.photons \
  simulate --photons 1e8 --albedo 0.9999999999 --out t.h5
expect_refused "albedo 1, escape radius 1e6 mfp, 1e8 photons" run.photons \
  simulate --photons 1e8 --albedo 1 --escape-radius 1e6 --out t.h5
# Long but possible: albedo 1 - 1e-6 takes up to 1e6 events a photon, 2e11 for 2e5 photons, about
# 17 min on 4 threads at 20 ns an event. It says so before it starts (its first line), then runs;
# killed here after two seconds.
timeout -s KILL 2 "$exe" searchlight --albedo 0.999999 --photons 2e5 --threads 4 --out long.h5 \
  >long.out 2>long.err
expected="searchlight: long.h5 may take long: up to 1e+06 events a photon (albedo 0.999999), "
expected+="2e+11 in all, about 17 min at 20 ns an event on 4 threads"
if [ "$(head -1 long.err | cut -c1-${#expected})" = "$expected" ]; then pass; else
  fail "a long run's warning before it starts: $(head -3 long.err)"
fi
# A semi-infinite slab of albedo 1 - 1e-6 too (its layers' highest albedo bounds its events).
printf '[geometry]\ntype = "slab"\n[[layers]]\nmu_a = 1e-4\nmu_s = 99.9999\ng = 0.9\nn = 1.4\n' \
  >long-slab.toml
printf 'thickness = inf\n[run]\nphotons = 200000\nthreads = 4\n' >>long-slab.toml
timeout -s KILL 2 "$exe" simulate long-slab.toml --out long-slab.h5 >long.out 2>long.err
expected="simulate: long-slab.h5 may take long: up to 1e+06 events a photon (the layers' highest "
expected+="albedo 0.999999), 2e+11 in all, about 17 min at 20 ns an event on 4 threads"
if [ "$(head -1 long.err | cut -c1-${#expected})" = "$expected" ]; then pass; else
  fail "a long slab run's warning before it starts: $(head -3 long.err)"
fi
# 1000 x 1000 values: a million points, counted from the lists before one is made.
{
  printf '[medium]\nalbedo = ['
  seq -s, 0.0001 0.0001 0.1 | tr -d '\n'
  printf ']\ng = ['
  seq -s, 0.0001 0.0001 0.1 | tr -d '\n'
  printf ']\n'
} >sweep-million.toml
expect_refused "a sweep of a million points" "medium.albedo x medium.g" \
  simulate --scene sweep-million.toml "${tiny[@]}" --out-dir sweep-million
printf '[run]\nseed = [%s]\n' "$(seq -s, 1 1001)" >sweep-1001.toml
expect_refused "a sweep of 1001 points, one over the limit" "run.seed" \
  simulate --scene sweep-1001.toml "${tiny[@]}" --out-dir sweep-1001

# --- 5. within the limits: runs, and an allocation that fails anyway is one line, exit 1 -------
if "$exe" simulate "${tiny[@]}" "${grid[@]}" --memory-limit 512M --out ok.h5 >/dev/null &&
  "$exe" info ok.h5 --memory-limit 512M >/dev/null; then
  pass
else
  fail "a small run under --memory-limit 512M did not run"
fi
if "$exe" simulate --photons 200 --batches 4 --threads 1 --albedo 1 --escape-radius 30 \
  "${grid[@]}" --out albedo1.h5 >/dev/null; then
  pass
else
  fail "albedo 1 with escape radius 30 mfp (~900 events per photon) did not run"
fi
# The estimate passes (--memory-limit 1T), the allocation cannot (4 GB of address space; not
# under AddressSanitizer, which reserves terabytes of address space itself).
if ldd "$exe" | grep -q libasan; then
  echo "note: AddressSanitizer build: the case of an allocation past the estimate is skipped"
else
(
  ulimit -v 4000000
  exec timeout -k 10 60 "$exe" simulate "${tiny[@]}" --tallies fluence --r-bins 100000 \
    --z-bins 10000 --memory-limit 1T --out oom.h5
) >"$scratch/stdout" 2>"$scratch/stderr"
status=$?
if [ $status -ne 1 ]; then
  fail "an allocation past the estimate: exit $status, expected 1: $(cat "$scratch/stderr")"
elif [ "$(error_lines "$scratch/stderr")" -ne 1 ] || ! grep -q "out of memory" "$scratch/stderr"; then
  fail "an allocation past the estimate: not one line saying so: $(cat "$scratch/stderr")"
elif compgen -G "oom.h5*" >/dev/null; then
  fail "an allocation past the estimate left a file"
else
  pass
fi
fi

report budget_limits
