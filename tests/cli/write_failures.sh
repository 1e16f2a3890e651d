#!/usr/bin/env bash
# Usage: write_failures.sh SCATTERLAB SOURCE_DIR
# Writes that fail and places that take no files, for every command that writes:
#   a write that fails (here a file size limit; a full tmpfs too where this may mount one):
#     exit 1, one line naming the output and the system's reason, the file that was at that path
#     byte for byte the same, no temporary left, no crash;
#   an output whose directory takes no new files (/proc, which refuses root too; a 0555
#     directory, which refuses others): exit 2 before any work, one line naming the flag and the
#     directory, nothing changed;
#   standard output that fails (/dev/full): exit 1 and one line; a reader that stopped reading:
#     a quiet end, by SIGPIPE, as other programs end;
#   a launcher's rank count set without a launcher (OMPI_COMM_WORLD_SIZE and the like): exit 2,
#     one line naming the variable, no file, no hang; in builds with and without MPI alike.
set -u
exe=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/harness.sh"
full=$scratch/full    # a small tmpfs, where one can be mounted
trap 'umount "$full" 2>/dev/null; rm -rf "$work" "$scratch"' EXIT

# Files of a few hundred kB: beyond the limits below.
large=(--theta-bins 12 --phi-bins 16 --r-bins 12 --z-bins 12)

snapshot() {
  find . -type f -print0 | sort -z | xargs -0 -r sha256sum
  find . | sort
}

# limited KIB COMMAND...: the command with files limited to KIB KiB. SIGXFSZ is ignored, and an
# ignored signal stays ignored across exec, so a write beyond the limit fails with EFBIG instead
# of killing the process. Its output in $scratch/stdout and $scratch/stderr.
limited() {
  local kib=$1
  shift
  (
    trap '' XFSZ
    ulimit -f "$kib"
    exec timeout 120 "$exe" "$@"
  ) >"$scratch/stdout" 2>"$scratch/stderr"
}

# expect_write_failure NAME PATH REASON KIB COMMAND...: exit 1, one line on stderr naming PATH
# and REASON, PATH as it was (or still absent), no temporary beside it, no other file changed
# except those named in the array `may_change`.
may_change=()
expect_write_failure() {
  local name=$1 path=$2 reason=$3 kib=$4
  shift 4
  snapshot | grep -v -F -e "${may_change[@]:-/nothing/}" >"$scratch/before"
  limited "$kib" "$@"
  local status=$?
  snapshot | grep -v -F -e "${may_change[@]:-/nothing/}" >"$scratch/after"
  if [ $status -ne 1 ]; then
    fail "$name: exit $status, expected 1: $(cat "$scratch/stderr")"
  elif grep -q -i "segmentation\|core dumped\|HDF5-DIAG" "$scratch/stderr"; then
    fail "$name: crashed: $(cat "$scratch/stderr")"
  elif ! grep -q -F -- "$path" "$scratch/stderr"; then
    fail "$name: the error does not name $path: $(cat "$scratch/stderr")"
  elif ! grep -q -F -- "$reason" "$scratch/stderr"; then
    fail "$name: the error does not say '$reason': $(cat "$scratch/stderr")"
  elif [ "$(error_lines "$scratch/stderr")" -ne 1 ]; then
    fail "$name: more than one line on stderr: $(cat "$scratch/stderr")"
  elif compgen -G "$(dirname "$path")/*.tmp-*" >/dev/null; then
    fail "$name: left a temporary: $(ls "$(dirname "$path")")"
  elif ! cmp -s "$scratch/before" "$scratch/after"; then
    fail "$name: files changed: $(diff "$scratch/before" "$scratch/after")"
  else
    pass
  fi
}

# expect_refused_saying NAME FIELD TEXT COMMAND...: as the harness's expect_refused, but the line
# must also say TEXT (and need not say what is accepted): exit 2 within a minute, one line naming
# FIELD and TEXT, nothing in the working directory changed, added or removed. ENV_SET, when set,
# is exported to the command.
expect_refused_saying() {
  local name=$1 field=$2 text=$3
  shift 3
  snapshot >"$scratch/before"
  timeout 60 env ${ENV_SET:-} "$exe" "$@" >"$scratch/stdout" 2>"$scratch/stderr"
  local status=$?
  snapshot >"$scratch/after"
  if [ $status -ne 2 ]; then
    fail "$name: exit $status, expected 2: $(cat "$scratch/stderr")"
  elif ! grep -q -F -- "$field" "$scratch/stderr" || ! grep -q -F -- "$text" "$scratch/stderr"
  then
    fail "$name: the error does not name $field and $text: $(cat "$scratch/stderr")"
  elif [ "$(error_lines "$scratch/stderr")" -ne 1 ]; then
    fail "$name: more than one line on stderr: $(cat "$scratch/stderr")"
  elif ! cmp -s "$scratch/before" "$scratch/after"; then
    fail "$name: files changed: $(diff "$scratch/before" "$scratch/after")"
  else
    pass
  fi
}

# The files lying about, which must come out untouched.
"$exe" simulate "${tiny[@]}" "${large[@]}" --seed 1 --out a.h5 >/dev/null || fail "setup: a.h5"
"$exe" simulate "${tiny[@]}" "${large[@]}" --seed 2 --out b.h5 >/dev/null || fail "setup: b.h5"
"$exe" simulate "${tiny[@]}" "${grid[@]}" --seed 3 --out old.h5 >/dev/null || fail "setup: old.h5"
write_tet_render_scene "$source_dir" 96
echo "the previous image" >old.exr
echo "the previous table" >old.csv

# --- a write that fails -------------------------------------------------------------------------
limit=16  # KiB: every file below is larger
expect_write_failure "simulate: --out over the size limit" old.h5 "File too large" $limit \
  simulate "${tiny[@]}" "${large[@]}" --out old.h5
expect_write_failure "searchlight: --out over the size limit" old.h5 "File too large" $limit \
  searchlight "${tiny[@]}" --r-bins 60 --z-bins 60 --out old.h5
expect_write_failure "merge: --out over the size limit" old.h5 "File too large" $limit \
  merge a.h5 b.h5 -o old.h5
expect_write_failure "simulate: checkpoint over the size limit" new.h5.checkpoint \
  "File too large" 4 simulate "${tiny[@]}" "${large[@]}" --out new.h5 --checkpoint-interval 1b
expect_write_failure "render: the OpenEXR image over the size limit" old.exr "File too large" 2 \
  render render.toml --samples 1 --light-samples 1 --threads 1 --out old.exr
expect_write_failure "fit: the CSV over the size limit" old.csv "File too large" 4 \
  fit a.h5 --models sg --csv old.csv
# Room for the copy of a.h5 that fit adds /fits to, and for its CSV (a new file), not for the
# file with /fits.
may_change=(./a-fits.csv)
expect_write_failure "fit: the rewritten file over the size limit" a.h5 "File too large" \
  $(($(stat -c %s a.h5) / 1024 + 4)) fit a.h5 --models sg --csv a-fits.csv
may_change=()

# Commands that write a directory of files: the one that fails is named and kept as it was (the
# others, each written whole, may be new).
expect_directory_write_failure() {
  local name=$1 directory=$2 kib=$3
  shift 3
  "$exe" "$@" >/dev/null 2>&1 || fail "$name: setup run failed"
  (cd "$directory" && sha256sum -- *) >"$scratch/before"
  limited "$kib" "$@"
  local status=$?
  local named
  named=$(sed -n "s/.*cannot write '\([^']*\)'.*/\1/p" "$scratch/stderr")
  if [ $status -ne 1 ]; then
    fail "$name: exit $status, expected 1: $(cat "$scratch/stderr")"
  elif [ "${named#"$directory"/}" = "$named" ] || ! grep -q "File too large" "$scratch/stderr"
  then
    fail "$name: the error names no file of $directory, or no reason: $(cat "$scratch/stderr")"
  elif [ "$(error_lines "$scratch/stderr")" -ne 1 ]; then
    fail "$name: more than one line on stderr: $(cat "$scratch/stderr")"
  elif ! grep -q -F "  ${named#"$directory"/}" "$scratch/before" ||
    [ "$(cd "$directory" && sha256sum -- "${named#"$directory"/}")" != \
      "$(grep -F "  ${named#"$directory"/}" "$scratch/before")" ]; then
    fail "$name: $named changed"
  elif compgen -G "$directory/*.tmp-*" >/dev/null; then
    fail "$name: left a temporary: $(ls "$directory")"
  else
    pass
  fi
}
# validate and report take minutes each in the unoptimised sanitizer build (3 min for one report
# section); their files go through the same write_whole_file as the cases above, and the Release
# suite runs them.
if ldd "$exe" | grep -q libasan; then
  echo "note: AddressSanitizer build: the validate and report write failures are skipped"
else
  expect_directory_write_failure "validate deon: a file over the size limit" validation 4 \
    validate deon --quick --threads 1 --out validation
  expect_directory_write_failure "report: a file over the size limit" report 1 \
    report --quick --section refractive_solver --out report
fi

# A full filesystem: a small tmpfs, where this may mount one (root, outside most containers).
mkdir -p "$full"
# Room for old.h5 and 8 kB more, not for a file of the large grid.
tmpfs_kib=$(($(stat -c %s old.h5) / 1024 + 12))
if [ "$(id -u)" -eq 0 ] &&
  mount -t tmpfs -o size=${tmpfs_kib}k scatterlab-full "$full" 2>/dev/null; then
  cp old.h5 "$full/run.h5" || fail "setup: old.h5 does not fit in the tmpfs"
  sha_before=$(sha256sum <"$full/run.h5")
  "$exe" simulate "${tiny[@]}" "${large[@]}" --out "$full/run.h5" >/dev/null 2>"$scratch/stderr"
  status=$?
  if [ $status -eq 1 ] && grep -q "No space left on device" "$scratch/stderr" &&
    grep -q -F "$full/run.h5" "$scratch/stderr" &&
    [ "$(sha256sum <"$full/run.h5")" = "$sha_before" ] &&
    ! compgen -G "$full/*.tmp-*" >/dev/null; then pass; else
    fail "full tmpfs: exit $status: $(cat "$scratch/stderr"; ls "$full")"
  fi
  umount "$full"
else
  echo "write_failures: no tmpfs can be mounted here; the size limit stands in for a full disk"
fi

# --- outputs where no file can be made ----------------------------------------------------------
expect_refused_saying "simulate: --out in /proc" --out "'/proc'" \
  simulate "${tiny[@]}" --out /proc/scatterlab.h5
expect_refused_saying "simulate: --checkpoint in /proc" --checkpoint "'/proc'" \
  simulate "${tiny[@]}" --out new.h5 --checkpoint /proc/scatterlab.ckpt
expect_refused_saying "simulate: --out-dir under /proc" --out-dir "'/proc'" \
  simulate "${tiny[@]}" --out-dir /proc/scatterlab-sweep
expect_refused_saying "searchlight: --out in /proc" --out "'/proc'" \
  searchlight "${tiny[@]}" --out /proc/scatterlab.h5
expect_refused_saying "merge: --out in /proc" --out "'/proc'" merge a.h5 b.h5 -o /proc/scatterlab.h5
expect_refused_saying "fit: --csv in /proc" --csv "'/proc'" fit a.h5 --csv /proc/scatterlab.csv
expect_refused_saying "render: --out in /proc" --out "'/proc'" render render.toml --out /proc/s.exr
expect_refused_saying "render --study: --out under /proc" --out "'/proc'" \
  render --study --quick render.toml --out /proc/scatterlab-study
expect_refused_saying "report: --out under /proc" --out "'/proc'" report --quick --out /proc/scatterlab
expect_refused_saying "validate deon: --out under /proc" --out "'/proc'" \
  validate deon --quick --out /proc/scatterlab
expect_refused_saying "validate searchlight: --out under /proc" --out "'/proc'" \
  validate searchlight --quick --out /proc/scatterlab
if [ "$(id -u)" -ne 0 ]; then
  mkdir locked
  chmod 0555 locked
  expect_refused_saying "simulate: --out in a 0555 directory" --out "locked'" \
    simulate "${tiny[@]}" --out locked/run.h5
  expect_refused_saying "report: --out under a 0555 directory" --out "locked'" \
    report --quick --out locked/report
  chmod 0755 locked
  rmdir locked
else
  echo "write_failures: running as root, which ignores permission bits: 0555 case skipped"
fi

# --- standard output ----------------------------------------------------------------------------
# /dev/full behind standard output (the shell's redirection; scatterlab is given no device path).
for args in "info a.h5" "--help" "simulate --help" "invert --Rd 0.5 --ld 2"; do
  # shellcheck disable=SC2086
  "$exe" $args >/dev/full 2>"$scratch/stderr"
  status=$?
  if [ $status -eq 1 ] && grep -q "standard output" "$scratch/stderr" &&
    grep -q "No space left on device" "$scratch/stderr" &&
    [ "$(error_lines "$scratch/stderr")" -eq 1 ]; then pass; else
    fail "$args >/dev/full: exit $status: $(cat "$scratch/stderr")"
  fi
done
# A reader that is gone: a pipe with no reader left (opened read-write, then the reader closed).
mkfifo "$scratch/pipe"
for sigpipe in default ignored; do
  exec 4<>"$scratch/pipe" 5>"$scratch/pipe"
  exec 4<&-
  if [ $sigpipe = ignored ]; then
    (
      trap '' PIPE
      exec "$exe" info a.h5
    ) >&5 2>"$scratch/stderr"
  else
    "$exe" info a.h5 >&5 2>"$scratch/stderr"
  fi
  status=$?
  exec 5>&-
  if [ $status -eq 141 ] && [ ! -s "$scratch/stderr" ]; then pass; else
    fail "info into a closed pipe, SIGPIPE $sigpipe: exit $status: $(cat "$scratch/stderr")"
  fi
done
"$exe" info a.h5 2>"$scratch/stderr" | head -c 10 >/dev/null
status=${PIPESTATUS[0]}
if { [ $status -eq 0 ] || [ $status -eq 141 ]; } && [ ! -s "$scratch/stderr" ]; then pass; else
  fail "info | head -c 10: exit $status: $(cat "$scratch/stderr")"
fi

# --- a launcher's variables without a launcher --------------------------------------------------
for variable in OMPI_COMM_WORLD_SIZE=4 PMI_SIZE=2 PMIX_SIZE=2 MPI_LOCALNRANKS=2 PMIX_RANK=0 \
  OMPI_COMM_WORLD_SIZE=1; do
  ENV_SET=$variable expect_refused_saying "stray $variable" "${variable%%=*}" "no MPI launcher" \
    simulate "${tiny[@]}" --out stray.h5
done
ENV_SET="OMPI_COMM_WORLD_SIZE=four PMIX_SERVER_URI2=nowhere" expect_refused_saying \
  "a launcher's rank count that is not a number" OMPI_COMM_WORLD_SIZE "four" \
  simulate "${tiny[@]}" --out stray.h5

report write_failures
