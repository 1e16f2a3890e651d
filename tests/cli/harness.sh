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
