# Shared by the e2e scripts that count checks (sourced, not run): a temporary folder removed on exit, and
# check(), which runs a command and counts it as passed or failed, printing FAIL with its description.
# The script ends with: echo "NAME: $passes passed, $failures failed"; [ "$failures" -eq 0 ]
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0 passes=0
check() { # description, then a command that must succeed
  local what=$1; shift
  if "$@"; then passes=$((passes + 1)); else echo "FAIL: $what"; failures=$((failures + 1)); fi
}
