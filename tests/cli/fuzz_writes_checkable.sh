#!/usr/bin/env bash
# pge fuzz writes a shrunk failing scene that pge check reads (tests/CMakeLists.txt,
# cli_fuzz_writes_checkable).
# 1. Case 31 of `pge fuzz --spin 10 --seed 1206` passes: it found E7 (docs/rotation.md: a spinning
#    box with restitution 0 on two collinear segments, a contact the exact paths still approached
#    after the impulse), fixed since; it exits 8 with the binary before the fix.
# 2. Case 96 of `pge fuzz --storms-fail --seed 1206` fails on an event storm (resting contact
#    between moving bodies, which the engine does not model: docs/events.md); the scene written
#    must be a valid scene file whose check finds the storm again (exit 4), not a bad scene file
#    (exit 3: the note was once written as an object). Once such resting contact is modelled the
#    fuzz finds nothing there and this test says so: point it at another failing case.
# Usage: fuzz_writes_checkable.sh PGE OUT_DIR
set -uo pipefail
pge=$1
out=$2
rm -rf "$out"
mkdir -p "$out"
"$pge" fuzz --spin 10 --seed 1206 --first 31 --cases 1 --out "$out/e7" -q
code=$?
if [[ $code -ne 0 ]]; then
  echo "fuzz case 31 of --spin 10 --seed 1206 exited $code, not 0: E7 (docs/rotation.md) is back" >&2
  exit 1
fi
"$pge" fuzz --storms-fail --seed 1206 --first 96 --cases 1 --out "$out" -q
code=$?
if [[ $code -ne 8 ]]; then
  echo "fuzz case 96 of --storms-fail --seed 1206 exited $code, not 8: no storm there any more? point this test at another failing case" >&2
  exit 1
fi
files=("$out"/*.json)
[[ -f ${files[0]} ]] || { echo "fuzz exited 8 but wrote no scene in $out" >&2; exit 1; }
"$pge" check -q "${files[0]}" >"$out/check.txt" 2>&1
code=$?
if [[ $code -ne 4 ]]; then
  echo "pge check on the written scene exited $code, not 4 (found the storm again):" >&2
  cat "$out/check.txt" >&2
  exit 1
fi
echo "fuzz case 31 (E7) passes; written scene ${files[0]##*/} read by pge check, storm found again (exit 4)"
