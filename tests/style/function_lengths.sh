#!/usr/bin/env bash
# No function in src/ over 150 lines (tests/style/function_lengths.py). First proves the scan fires: of two
# functions of 150 and 151 lines, with braces in a comment and a string to trip a naive count, it must name the
# longer one only. Usage: function_lengths.sh SOURCE_DIR
set -uo pipefail
root=$1
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{
  echo 'namespace probe {'
  echo 'int justRight(int x) {'; for _ in $(seq 148); do echo '    x += 1; // }'; done; echo '}'
  echo 'struct Holder {'
  echo '    int tooLong(int x) const {'; for _ in $(seq 149); do echo '        x += sizeof("}{");'; done; echo '    }'
  echo '};'
  echo '}'
} >"$tmp/probe.cc"
out=$(python3 "$here/function_lengths.py" 150 "$tmp/probe.cc")
if [ "$(grep -c 'lines, over' <<<"$out")" = 1 ] && grep -q 'tooLong is 151 lines' <<<"$out"; then
  echo "ok: the scan names the 151-line function and not the 150-line one"
else
  echo "FAIL: the scan missed the probe's 151-line function or named the 150-line one:"
  echo "$out"
  exit 1
fi
python3 "$here/function_lengths.py" 150 "$root/src"
