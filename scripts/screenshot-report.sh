#!/usr/bin/env bash
# scripts/screenshot-report.sh [PAGE.html [OUT.png]]
#
# A screenshot of a `pge report` page as headless Chromium draws it, the whole height of the
# page, 1200 px wide (default: out/report/index.html to out/report/screenshot.png), and the check
# that every chart on it loads and no label overlaps another or is cut off (the checker,
# tests/tools/report_layout_check.sh, names each finding; run it with --help for more).
# Exit codes: 0 written and clean; 1 written, but the check found something (listed); 2 bad
# command line or no such page; 3 Chromium failed; 77 Chromium (or python3) is not installed
# (set CHROMIUM=/path/to/chromium for another than /usr/bin/chromium).
set -u
case ${1-} in -h|--help) sed -n '2,/^set -u/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;; esac
[[ $# -le 2 ]] || { echo "usage: $0 [PAGE.html [OUT.png]]" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
page=${1:-$root/out/report/index.html}
shot=${2:-$(dirname "$page")/screenshot.png}
"$root/tests/tools/report_layout_check.sh" --charts "" --screenshot "$shot" "$page"
