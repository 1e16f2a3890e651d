# Sourced by the CLI test scripts: a scratch directory (removed on exit) to work in, and
# pass/fail counting; `report NAME` prints the tally and returns non-zero on any failure.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0 passed=0
pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
report() {
  echo "$1: $passed passed, $failures failed"
  [ $failures -eq 0 ]
}

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

# expect_refused_untouched NAME FIELD COMMAND...: exit status 2 within a minute (no hang, no
# allocation that swaps), one line on stderr naming FIELD and what is accepted, and every file
# under the working directory byte for byte as before, with none added or removed.
notes="$work/.refusal-notes"  # the check's own files, left out of what it watches
tree_digest() {
  find . -path ./.refusal-notes -prune -o -type f -print0 | sort -z | xargs -0 -r sha256sum
  find . -path ./.refusal-notes -prune -o -print | sort
}
expect_refused_untouched() {
  local name=$1 field=$2
  shift 2
  mkdir -p "$notes"
  tree_digest >"$notes/before"
  timeout -k 10 60 "$exe" "$@" >"$notes/stdout" 2>"$notes/stderr"
  local status=$?
  tree_digest >"$notes/after"
  if [ $status -ne 2 ]; then
    fail "$name: exit $status, expected 2: $(cat "$notes/stderr")"
  elif ! grep -q -- "$field" "$notes/stderr"; then
    fail "$name: the error does not name $field: $(cat "$notes/stderr")"
  elif [ "$(grep -c . "$notes/stderr")" -ne 1 ]; then
    fail "$name: more than one line on stderr: $(cat "$notes/stderr")"
  elif ! grep -q "accepted\|--help" "$notes/stderr"; then
    fail "$name: the error does not say what is accepted: $(cat "$notes/stderr")"
  elif ! cmp -s "$notes/before" "$notes/after"; then
    fail "$name: files changed: $(diff "$notes/before" "$notes/after")"
  else
    pass
  fi
}
