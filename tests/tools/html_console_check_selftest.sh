#!/usr/bin/env bash
# html_console_check_selftest.sh: the page checker catches what it must and passes what it
# must: a console.error, an uncaught exception and a missing <img> each fail; a clean page (one
# that calls console.log and console.info) passes; and each failure names its page. Exits 77
# when Chromium is missing (the checker's own skip code).
set -u
here=$(cd "$(dirname "$0")" && pwd)
checker=$here/html_console_check.sh
cases=$here/html_check_cases
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

failures=0
# expect CASE WANTED_EXIT [TEXT]: the checker on CASE.html exits WANTED_EXIT and prints TEXT.
expect() {
  local page=$cases/$1.html wanted=$2 text=${3:-}
  "$checker" "$page" >"$out/$1.log" 2>&1
  local code=$?
  if [[ $code -eq 77 ]]; then
    cat "$out/$1.log"
    echo "skip: Chromium missing"
    exit 77
  fi
  if [[ $code -ne $wanted ]]; then
    echo "FAIL: $1.html: checker exited $code, expected $wanted; it said:"
    sed 's/^/    /' "$out/$1.log"
    failures=$((failures + 1))
  elif [[ -n $text ]] && ! grep -qF -- "$text" "$out/$1.log"; then
    echo "FAIL: $1.html: checker output lacks \"$text\"; it said:"
    sed 's/^/    /' "$out/$1.log"
    failures=$((failures + 1))
  else
    echo "ok: $1.html: exit $code"
  fi
}

expect good 0 "good.html: ok"
expect console-error 1 "console.error: x"
expect exception 1 "uncaught exception: Error: boom"
expect missing-resource 1 "missing.png"

# Several pages at once: one bad page fails the run and is named; the good one is still ok.
"$checker" "$cases/good.html" "$cases/exception.html" >"$out/both.log" 2>&1
code=$?
if [[ $code -ne 1 ]] || ! grep -q "exception.html: FAIL" "$out/both.log" || ! grep -q "good.html: ok" "$out/both.log"; then
  echo "FAIL: good + exception: exit $code; the checker said:"
  sed 's/^/    /' "$out/both.log"
  failures=$((failures + 1))
else
  echo "ok: good + exception: exit 1, the bad page named"
fi

# Chromium missing: exit 77 with a message, whatever the pages.
CHROMIUM=$out/no-such-chromium "$checker" "$cases/good.html" >"$out/none.log" 2>&1
code=$?
if [[ $code -ne 77 ]] || ! grep -q "not found" "$out/none.log"; then
  echo "FAIL: without Chromium the checker exited $code (expected 77 and a message)"
  failures=$((failures + 1))
else
  echo "ok: without Chromium: exit 77"
fi

[[ $failures -eq 0 ]] || { echo "$failures checks failed"; exit 1; }
echo "ok: the checker fails console errors, exceptions and missing resources, and passes a clean page"
