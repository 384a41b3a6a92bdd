#!/usr/bin/env bash
# report_layout_check_selftest.sh: the report layout checker catches what it must and passes what
# it must, on hand-made pages shaped like pge report's (charts as <img alt="TITLE"
# src="data:image/svg+xml;base64,...">, tests/tools/layout_check_cases/*.svg): clean charts pass
# and the screenshot is a PNG; two overlapping labels fail, both named; a label cut off at the
# edge fails; a chart named by --charts but absent fails; without Chromium it exits 77 (the
# checker's own skip code, which this test passes on).
set -u
here=$(cd "$(dirname "$0")" && pwd)
checker=$here/report_layout_check.sh
cases=$here/layout_check_cases
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# page NAME TITLE:SVG...: a page with one chart per argument.
page() {
  local name=$1 html
  shift
  html='<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>t</title></head><body><h1>t</h1>'
  for chart in "$@"; do
    html+="<h2>${chart%%:*}</h2><img alt=\"${chart%%:*}\" src=\"data:image/svg+xml;base64,$(base64 -w0 "$cases/${chart#*:}")\">"
  done
  printf '%s</body></html>\n' "$html" >"$out/$name.html"
}
page clean "One:clean.svg" "Two:clean.svg"
page overlap "One:clean.svg" "Crowded:overlap.svg"
page cutoff "Cut:cutoff.svg"

failures=0
# expect NAME WANTED_EXIT TEXT [checker options...]: the checker on NAME.html exits WANTED_EXIT and prints TEXT.
expect() {
  local name=$1 wanted=$2 text=$3
  shift 3
  "$checker" "$@" "$out/$name.html" >"$out/$name.log" 2>&1
  local code=$?
  if [[ $code -eq 77 ]]; then
    cat "$out/$name.log"
    echo "skip: Chromium missing"
    exit 77
  fi
  if [[ $code -ne $wanted ]] || ! grep -qF -- "$text" "$out/$name.log"; then
    echo "FAIL: $name.html $*: checker exited $code (expected $wanted) or its output lacks \"$text\"; it said:"
    sed 's/^/    /' "$out/$name.log"
    failures=$((failures + 1))
  else
    echo "ok: $name.html $*: exit $code, \"$text\""
  fi
}

expect clean 0 "clean.html: ok (2 charts, 0 problems)" --charts "One,Two" --screenshot "$out/clean.png"
if [[ "$(head -c 8 "$out/clean.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" != 89504e470d0a1a0a ]]; then
  echo "FAIL: the screenshot $out/clean.png is not a PNG"
  failures=$((failures + 1))
else
  echo "ok: the screenshot is a PNG"
fi
expect overlap 1 'chart "Crowded": labels overlap: "60 Hz 8+3" and "240 Hz 50+20"' --charts "One,Crowded"
expect cutoff 1 'chart "Cut": label cut off at the edge: "too long to fit in the picture"' --charts Cut
expect clean 1 'chart missing: "Three"' --charts "One,Two,Three"

# exits NAME WANTED_EXIT TEXT COMMAND...: COMMAND exits WANTED_EXIT and prints TEXT (no skip).
exits() {
  local name=$1 wanted=$2 text=$3 code
  shift 3
  "$@" >"$out/$name.log" 2>&1
  code=$?
  if [[ $code -ne $wanted ]] || ! grep -qF -- "$text" "$out/$name.log"; then
    echo "FAIL: $name: exit $code (expected $wanted) or no \"$text\" in: $(cat "$out/$name.log")"
    failures=$((failures + 1))
  else
    echo "ok: $name: exit $code"
  fi
}
exits "without Chromium" 77 "not found" env CHROMIUM="$out/no-such-chromium" "$checker" "$out/clean.html"
exits "a missing page" 2 "no such page" "$checker" "$out/no-such-page.html"

if [[ $failures -gt 0 ]]; then
  echo "$failures selftest case(s) failed"
  exit 1
fi
echo "report_layout_check selftest: all cases pass"
