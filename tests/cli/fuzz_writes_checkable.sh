#!/usr/bin/env bash
# pge fuzz writes a shrunk failing scene that pge check reads (tests/CMakeLists.txt,
# cli_fuzz_writes_checkable): case 31 of `pge fuzz --spin 10 --seed 1206` fails today (a spinning
# box with restitution 0 on two collinear segments, docs/rotation.md E7, a known failure); the
# scene written must be a valid scene file whose check finds the failure again (exit 7), not a bad
# scene file (exit 3: the note was once written as an object). When E7 is fixed the fuzz finds
# nothing here and this test says so: point it at another failing case.
# Usage: fuzz_writes_checkable.sh PGE OUT_DIR
set -uo pipefail
pge=$1
out=$2
rm -rf "$out"
mkdir -p "$out"
"$pge" fuzz --spin 10 --seed 1206 --first 31 --cases 1 --out "$out" -q
code=$?
if [[ $code -ne 8 ]]; then
  echo "fuzz case 31 of seed 1206 exited $code, not 8: E7 fixed? point this test at another failing case" >&2
  exit 1
fi
files=("$out"/*.json)
[[ -f ${files[0]} ]] || { echo "fuzz exited 8 but wrote no scene in $out" >&2; exit 1; }
"$pge" check -q "${files[0]}" >"$out/check.txt" 2>&1
code=$?
if [[ $code -ne 7 ]]; then
  echo "pge check on the written scene exited $code, not 7 (found the failure again):" >&2
  cat "$out/check.txt" >&2
  exit 1
fi
echo "written scene ${files[0]##*/} read by pge check, failure found again (exit 7)"
