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
