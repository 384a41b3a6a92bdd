#!/usr/bin/env bash
# report_layout_check.sh [--charts LIST] [--screenshot FILE.png] [--width PX] INDEX.html
#
# Looks at a `pge report` page the way a reader does, in headless Chromium, and fails (exit 1)
# naming the chart and the labels when:
#   - a chart named in LIST (comma-separated <img alt> titles; default: every chart pge report
#     can draw) is missing from the page, or its image does not load or renders with no size;
#   - two text labels of a chart overlap (their boxes as Chromium lays them out, fonts and all,
#     intersect by more than 1.5 px across and a quarter of the line height down: gnuplot's key
#     lines and a row of tick labels sit closer than their boxes' line height, and are fine);
#   - a label sticks out of its chart (cut off at the picture's edge).
# With --screenshot, it also writes a PNG of the whole page (all its height, --width wide, default
# 1200 px) as Chromium draws it.
#
# How: the plots are SVG images inlined in the page (data: URLs, which a script cannot look
# into), so the checker writes a measuring page beside the report with every chart's SVG inlined
# in the DOM and a small script that takes getBoundingClientRect() of every <text> and writes the
# overlaps into the DOM; `chromium --headless --dump-dom` prints that DOM. A second page, the
# report itself plus a script, says whether every chart image loaded and how tall the page is
# (for the screenshot). Measuring the layout, not pixels: a label over a line is fine, a label
# over a label is not, and the test says which.
#
# Exit codes: 0 every chart present and clean (and the screenshot written); 1 a chart missing,
# two labels overlapping or a label cut off (each named); 2 bad command line or no such page;
# 77 (CTest's skip code) when Chromium ($CHROMIUM, default /usr/bin/chromium) or python3 is
# missing; 3 Chromium failed (its output shown).
set -u

charts="Speed against error,Error CDFs,Energy drift over a long run,Events per second against body count,Against Box2D and Chipmunk"
shot="" width=1200 page=""
usage() { sed -n '2,2p' "$0" | sed 's/^# /usage: /'; }
while [[ $# -gt 0 ]]; do
  case $1 in
    --charts) charts=${2-}; shift 2 || { usage >&2; exit 2; } ;;
    --screenshot) shot=${2-}; shift 2 || { usage >&2; exit 2; } ;;
    --width) width=${2-}; shift 2 || { usage >&2; exit 2; } ;;
    -h|--help) sed -n '2,/^set -u/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "report_layout_check: unknown option $1" >&2; usage >&2; exit 2 ;;
    *) [[ -z $page ]] || { usage >&2; exit 2; }; page=$1; shift ;;
  esac
done
[[ -n $page ]] || { usage >&2; exit 2; }
[[ -f $page ]] || { echo "report_layout_check: no such page: $page" >&2; exit 2; }
[[ $width =~ ^[0-9]+$ ]] || { echo "report_layout_check: --width wants pixels, got $width" >&2; exit 2; }
source "$(dirname "$0")/chromium_or_skip.sh" report_layout_check

work=$(mktemp -d "${TMPDIR:-/tmp}/report_layout_check.XXXXXX")
trap 'rm -rf "$work"' EXIT

python3 - "$chromium" "$work" "$page" "$charts" "$shot" "$width" <<'PY'
import base64, html, json, os, re, subprocess, sys

chromium, work, page, charts, shot, width = sys.argv[1:7]
width = int(width)
wanted = [c.strip() for c in charts.split(",") if c.strip()]
text = open(page, encoding="utf-8").read()


def chrome(*args, url):
    cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           "--user-data-dir=" + os.path.join(work, "profile"), "--no-first-run", "--disable-extensions",
           "--disable-sync", "--disable-background-networking", "--disable-component-update",
           "--mute-audio", "--virtual-time-budget=10000", *args, url]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=180)
    if p.returncode != 0:
        sys.stderr.write(p.stderr.decode(errors="replace")[-3000:])
        print(f"report_layout_check: Chromium exited {p.returncode} on {url}")
        sys.exit(3)
    return p.stdout.decode(errors="replace")


def result_of(dom, url):
    m = re.search(r'<pre id="layout-result">(.*?)</pre>', dom, re.S)
    if not m:
        print(f"report_layout_check: the measuring script left no result in {url}")
        sys.exit(3)
    return json.loads(html.unescape(m.group(1)))


# The report's charts: <img alt="TITLE" src="data:image/svg+xml;base64,...">.
images = [(html.unescape(alt), base64.b64decode(data).decode("utf-8"))
          for alt, data in re.findall(r'<img alt="([^"]*)" src="data:image/svg\+xml;base64,([^"]*)"', text)]
problems = []
present = {alt for alt, _ in images}
for c in wanted:
    if c not in present:
        problems.append(f"chart missing: \"{c}\" (no <img alt=\"{c}\"> with an inline SVG)")

# 1. The report itself in the browser: every image loaded and drawn, and the page's height.
probe = """
<script>
window.addEventListener('load', () => {
  const out = {height: Math.ceil(document.documentElement.scrollHeight), images: []};
  for (const img of document.images)
    out.images.push({alt: img.alt, loaded: img.complete && img.naturalWidth > 0,
                     width: img.getBoundingClientRect().width, height: img.getBoundingClientRect().height});
  const pre = document.createElement('pre');
  pre.id = 'layout-result';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
});
</script>
"""
# (a copy in the scratch directory: the page is self-contained, pge report's test sees to that)
copy = os.path.join(work, "page.html")
with open(copy, "w", encoding="utf-8") as f:
    f.write(text.replace("</body>", probe + "</body>") if "</body>" in text else text + probe)
url = "file://" + copy
page_result = result_of(chrome(f"--window-size={width},900", "--dump-dom", url=url), url)
for img in page_result["images"]:
    if not img["loaded"] or img["width"] < 10 or img["height"] < 10:
        problems.append(f"chart \"{img['alt']}\" did not load or has no size in the browser "
                        f"({img['width']:.0f} x {img['height']:.0f} px)")

# 2. The charts inlined, their labels measured.
blocks = []
for k, (alt, svg) in enumerate(images):
    svg = re.sub(r"<\?xml[^>]*\?>", "", svg)
    svg = re.sub(r"<!DOCTYPE[^>]*>", "", svg, flags=re.S)
    blocks.append(f'<div class="chart" data-title="{html.escape(alt)}">{svg}</div>')
measure = """<!DOCTYPE html><html><head><meta charset="utf-8"><style>body{margin:0}.chart{margin:0 0 20px 0}</style></head>
<body>
%s
<script>
const out = [];
for (const div of document.querySelectorAll('div.chart')) {
  const svg = div.querySelector('svg');
  const frame = svg.getBoundingClientRect();
  const labels = [];
  for (const t of svg.querySelectorAll('text')) {
    const s = t.textContent.replace(/\\s+/g, ' ').trim();
    if (!s) continue;
    const r = t.getBoundingClientRect();
    if (r.width <= 0 || r.height <= 0) continue;
    labels.push({text: s, x0: r.left, y0: r.top, x1: r.right, y1: r.bottom});
  }
  const overlaps = [];
  for (let i = 0; i < labels.length; ++i)
    for (let j = i + 1; j < labels.length; ++j) {
      const a = labels[i], b = labels[j];
      const across = Math.min(a.x1, b.x1) - Math.max(a.x0, b.x0);
      const down = Math.min(a.y1, b.y1) - Math.max(a.y0, b.y0);
      const line = Math.min(a.y1 - a.y0, b.y1 - b.y0);
      if (across > 1.5 && down > 0.25 * line) overlaps.push([a.text, b.text, across, down]);
    }
  const outside = labels.filter(l => l.x0 < frame.left - 1 || l.y0 < frame.top - 1 ||
                                     l.x1 > frame.right + 1 || l.y1 > frame.bottom + 1).map(l => l.text);
  out.push({title: div.dataset.title, labels: labels.length, overlaps, outside});
}
const pre = document.createElement('pre');
pre.id = 'layout-result';
pre.textContent = JSON.stringify(out);
document.body.appendChild(pre);
</script>
</body></html>
""" % "\n".join(blocks)
measure_path = os.path.join(work, "measure.html")
with open(measure_path, "w", encoding="utf-8") as f:
    f.write(measure)
url = "file://" + measure_path
for chart in result_of(chrome(f"--window-size={width},900", "--dump-dom", url=url), url):
    for a, b, across, down in chart["overlaps"]:
        problems.append(f"chart \"{chart['title']}\": labels overlap: \"{a}\" and \"{b}\" "
                        f"({across:.1f} x {down:.1f} px)")
    for t in chart["outside"]:
        problems.append(f"chart \"{chart['title']}\": label cut off at the edge: \"{t}\"")
    print(f"report_layout_check: chart \"{chart['title']}\": {chart['labels']} labels, "
          f"{len(chart['overlaps'])} overlapping pairs, {len(chart['outside'])} cut off")

if shot:
    height = max(600, min(int(page_result["height"]) + 20, 30000))
    chrome(f"--window-size={width},{height}", "--screenshot=" + os.path.abspath(shot),
           url="file://" + os.path.abspath(page))
    if not os.path.isfile(shot) or os.path.getsize(shot) == 0:
        print(f"report_layout_check: Chromium wrote no screenshot {shot}")
        sys.exit(3)
    print(f"report_layout_check: screenshot {shot} ({width} x {height} px)")

for p in problems:
    print("  " + p)
print(f"report_layout_check: {page}: " + ("FAIL" if problems else "ok") +
      f" ({len(images)} charts, {len(problems)} problems)")
sys.exit(1 if problems else 0)
PY
