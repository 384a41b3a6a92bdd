#!/usr/bin/env bash
# Runs a command that must fail cleanly: exit code EXPECTED (not a crash or a signal), exactly
# one line on stderr, containing every given substring.
# Usage: expect_error.sh EXPECTED_EXIT "substring" ... -- command args...
set -u
expected=$1; shift
needles=()
while [[ $# -gt 0 && "$1" != "--" ]]; do needles+=("$1"); shift; done
shift
err=$(mktemp)
"$@" >/dev/null 2>"$err"
code=$?
status=0
if [[ $code -ne $expected ]]; then echo "FAIL: exit code $code, expected $expected"; status=1; fi
lines=$(wc -l <"$err")
if [[ $lines -ne 1 ]]; then echo "FAIL: $lines lines on stderr, expected 1"; status=1; fi
for n in "${needles[@]}"; do
  if ! grep -qF -- "$n" "$err"; then echo "FAIL: stderr lacks: $n"; status=1; fi
done
echo "stderr: $(cat "$err")"
rm -f "$err"
exit $status
