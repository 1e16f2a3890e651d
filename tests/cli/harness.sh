# Sourced by the CLI test scripts: a scratch directory (removed on exit) to work in, another for
# the checks' own notes (outside the one they watch), and pass/fail counting; `report NAME`
# prints the tally and returns non-zero on any failure.
work=$(mktemp -d)
scratch=$(mktemp -d)
trap 'rm -rf "$work" "$scratch"' EXIT
cd "$work" || exit 1
failures=0 passed=0
pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
report() {
  echo "$1: $passed passed, $failures failed"
  [ $failures -eq 0 ]
}

# error_lines FILE: the lines of FILE that are not progress lines ("simulate: 0/4 batches,
# started; ..."), which a command off a terminal writes to stderr once its work has begun.
error_lines() { grep -cvE '^[a-z][a-z -]*: [0-9]+/[0-9]+ ' "$1"; }

# expect_command_error COMMAND NAME FIELD ARGS...: exit status 2, one line on stderr naming
# FIELD, and no output file (nor a temporary one). The run gets the arguments in the array
# `small` (set by the script; a small run by default) and --out $work/NAME.h5.
expect_command_error() {
  local command=$1 name=$2 field=$3
  shift 3
  local status=0
  [ -n "${small+set}" ] || small=(--photons 1000 --batches 4)
  "$exe" "$command" "${small[@]}" --out "$work/$name.h5" "$@" >"$work/stdout" 2>"$work/stderr" ||
    status=$?
  if [ "$status" -ne 2 ]; then
    fail "$name: exit status $status, not 2: $(cat "$work/stderr")"
  elif ! grep -q -- "$field" "$work/stderr"; then
    fail "$name: error does not name $field: $(cat "$work/stderr")"
  elif [ "$(grep -c . "$work/stderr")" -ne 1 ]; then
    fail "$name: more than one line of error: $(cat "$work/stderr")"
  elif compgen -G "$work/$name.h5*" >/dev/null; then
    fail "$name: left a file behind"
  else
    pass
  fi
}

# snapshot: the sha256 of every file under the working directory, and every path in it.
snapshot() {
  find . -type f -print0 | sort -z | xargs -0 -r sha256sum
  find . | sort
}

# expect_refused NAME FIELD COMMAND...: exit 2 (within a minute: no hang), FIELD named in the one
# line on stderr with what is accepted (or the flag it excludes), and nothing in the working
# directory changed, added or removed. The script sets `scratch`, a directory outside the one
# watched, for the notes. ENV_SET, when set, is passed to `env` for the command.
expect_refused() {
  local name=$1 field=$2
  shift 2
  snapshot >"$scratch/before"
  # shellcheck disable=SC2086 # ENV_SET is a list of NAME=VALUE words
  timeout -k 10 60 env ${ENV_SET:-} "$exe" "$@" >"$scratch/stdout" 2>"$scratch/stderr"
  local status=$?
  snapshot >"$scratch/after"
  if [ $status -ne 2 ]; then
    fail "$name: exit $status, expected 2: $(cat "$scratch/stderr")"
  elif ! grep -q -- "$field" "$scratch/stderr"; then
    fail "$name: the error does not name $field: $(cat "$scratch/stderr")"
  elif [ "$(grep -c . "$scratch/stderr")" -ne 1 ]; then
    fail "$name: more than one line on stderr: $(cat "$scratch/stderr")"
  elif ! grep -q "accepted\|excludes\|--help" "$scratch/stderr"; then
    fail "$name: the error does not say what is accepted: $(cat "$scratch/stderr")"
  elif ! cmp -s "$scratch/before" "$scratch/after"; then
    fail "$name: files changed: $(diff "$scratch/before" "$scratch/after")"
  else
    pass
  fi
}

# The small runs of the refusal scripts: every refusal comes before any photon, so these need only
# be valid.
tiny=(--photons 2000 --batches 4 --threads 1)
grid=(--theta-bins 6 --phi-bins 8 --r-bins 4 --z-bins 4)

# write_tet_render_scene SOURCE_DIR SIDE: tet.obj, a closed tetrahedron, and render.toml, the tile
# scene's settings rendering it at SIDE x SIDE pixels.
write_tet_render_scene() {
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >tet.obj
  sed -e '/^\[mesh\]/,/^$/c [mesh]\nshape = "obj"\npath = "tet.obj"\nnormals = "flat"\n' \
    -e "s/^width = .*/width = $2/" -e "s/^height = .*/height = $2/" \
    "$1/data/scenes/tile.toml" >render.toml
}

# expect_info NAME FILE PATTERN...: `info FILE` shows every pattern (extended regex).
expect_info() {
  local name=$1 file=$2
  shift 2
  "$exe" info "$file" >"$work/info" 2>&1 || { fail "$name: info failed: $(cat "$work/info")"; return; }
  for pattern in "$@"; do
    if ! grep -Eq -- "$pattern" "$work/info"; then
      fail "$name: info lacks '$pattern': $(cat "$work/info")"
      return
    fi
  done
  pass
}
