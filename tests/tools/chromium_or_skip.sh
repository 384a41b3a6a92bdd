# Sourced by the page checkers (html_console_check.sh, report_layout_check.sh) with their name as
# $1: sets chromium to $CHROMIUM (default /usr/bin/chromium), or exits 77 (CTest's skip code) with
# a message when Chromium or python3 is missing.
chromium=${CHROMIUM:-/usr/bin/chromium}
if [[ ! -x $chromium ]]; then
  echo "$1: Chromium not found at $chromium (install the Debian package 'chromium' or set" \
       "CHROMIUM=/path/to/chromium); skipping" >&2
  exit 77
fi
if ! command -v python3 >/dev/null; then
  echo "$1: python3 not found; skipping" >&2
  exit 77
fi
