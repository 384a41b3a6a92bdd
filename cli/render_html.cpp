// `pge render`, the page: a self-contained HTML page that animates a run on a canvas beside its
// SVG picture (no network, no external files).
#include "render_parts.hpp"
#include "trace.hpp"

#include <fmt/core.h>

#include <string>

namespace pge::cli::render {
namespace {

// The animation's data: the frame, each body's shape, color and samples (times, and positions in
// picture coordinates), and the marks as one flat array t, x, y, a, b, t, x, ... (flat arrays
// keep a 1000-body page small and its binary searches simple).
std::string animation_json(const Run& run, const View& v) {
  const Scene& scene = run.scene();
  const std::vector<std::string> colors = body_colors(scene);
  std::string out = fmt::format(
      "{{\"name\":{},\"end\":{},\"view\":[{},{},{},{}],\"fixed_fill\":\"{}\",\"fixed_stroke\":\"{}\","
      "\"mark_color\":\"{}\",\"bodies\":[\n",
      json_quoted(scene_title(run)), v.t(run.end), v.len(-v.margin), v.len(-v.margin), v.len(v.box_width()),
      v.len(v.box_height()), kFixedFill, kFixedStroke, kMarkColor);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    out += fmt::format("{}{{\"id\":{},\"color\":{},", i ? ",\n" : "", json_quoted(b.id),
                       b.fixed ? "null" : json_quoted(colors[i]));
    switch (b.shape) {
      case ShapeKind::Circle: out += fmt::format("\"shape\":\"circle\",\"r\":{}", v.len(b.radius)); break;
      case ShapeKind::Segment:
      case ShapeKind::Polygon: {
        // A turning body's vertices are about its pivot (its samples' p), turned by "a".
        const std::vector<Vec2d>& vs = !run.turning[i].empty()          ? run.turning[i]
                                       : b.shape == ShapeKind::Polygon ? b.vertices
                                                                        : std::vector<Vec2d>{b.a, b.b};
        out += fmt::format("\"shape\":\"{}\",\"v\":[", b.shape == ShapeKind::Polygon ? "polygon" : "segment");
        for (std::size_t k = 0; k < vs.size(); ++k) out += fmt::format("{}{},{}", k ? "," : "", v.len(vs[k].x), v.len(vs[k].y));
        out += ']';
        break;
      }
    }
    std::string times, points, angles;
    for (const Sample& s : run.paths[i]) {
      times += (times.empty() ? "" : ",") + v.t(s.t);
      points += (points.empty() ? "" : ",") + v.x(s.p.x) + "," + v.y(s.p.y);
      angles += fmt::format("{}{:.9g}", angles.empty() ? "" : ",", s.angle);
    }
    out += fmt::format(",\"t\":[{}],\"p\":[{}]", times, points);
    if (!run.turning[i].empty()) out += fmt::format(",\"a\":[{}]", angles);
    out += '}';
  }
  out += "],\n\"marks\":[";
  for (std::size_t k = 0; k < run.marks.size(); ++k) {
    const Mark& mk = run.marks[k];
    out += fmt::format("{}{},{},{},{},{}", k ? "," : "", v.t(mk.t), v.x(mk.p.x), v.y(mk.p.y), mk.a, mk.b);
  }
  out += "]}";
  // '<' only occurs inside JSON strings, where \u003c means the same: no "</script>" can end the
  // element early.
  std::string safe;
  safe.reserve(out.size());
  for (const char ch : out) {
    if (ch == '<')
      safe += "\\u003c";
    else
      safe += ch;
  }
  return safe;
}

// The page's script: plays the samples on the canvas (positions interpolated linearly between
// samples, marks flashing as they happen), with play/pause and a time slider. Everything it
// draws comes from the JSON data; nothing is fetched.
constexpr const char* kAnimationScript = R"JS(
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("pge-data").textContent);
  const canvas = document.getElementById("pge-canvas");
  const button = document.getElementById("pge-play");
  const slider = document.getElementById("pge-time");
  const clock = document.getElementById("pge-clock");
  const ctx = canvas.getContext("2d");
  const [vx, vy, vw, vh] = data.view;
  const end = data.end;
  // Simulated seconds per real second: real time for short runs; longer runs play in 20 s.
  const speed = end > 20 ? end / 20 : 1;
  const flash = 0.3 * speed;  // how long (simulated) a collision mark stays visible
  const cssW = canvas.width, cssH = canvas.height;
  const ratio = window.devicePixelRatio || 1;
  canvas.style.width = cssW + "px";
  canvas.style.height = cssH + "px";
  canvas.width = Math.round(cssW * ratio);
  canvas.height = Math.round(cssH * ratio);
  const scale = Math.min(cssW / vw, cssH / vh);
  const ox = (cssW - vw * scale) / 2, oy = (cssH - vh * scale) / 2;
  const X = (x) => ox + (x - vx) * scale;
  const Y = (y) => cssH - oy - (y - vy) * scale;

  // The index of the last element of the sorted array `a` (with stride `k`) that is <= t, or -1.
  function lastAtOrBefore(a, t, k) {
    let lo = 0, hi = a.length / k;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (a[mid * k] <= t) lo = mid + 1; else hi = mid;
    }
    return lo - 1;
  }
  // [x, y, sample index, angle]: a turning body's angle grows linearly between samples (its
  // rate changes only at collisions, which are samples), so interpolating it is exact.
  function position(b, t) {
    const i = lastAtOrBefore(b.t, t, 1);
    const angle = (k) => (b.a ? b.a[k] : 0);
    if (i < 0) return [b.p[0], b.p[1], 0, angle(0)];
    if (i + 1 >= b.t.length) return [b.p[2 * i], b.p[2 * i + 1], i, angle(i)];
    const t0 = b.t[i], t1 = b.t[i + 1];
    const f = t1 > t0 ? (t - t0) / (t1 - t0) : 1;
    return [b.p[2 * i] + f * (b.p[2 * i + 2] - b.p[2 * i]), b.p[2 * i + 1] + f * (b.p[2 * i + 3] - b.p[2 * i + 1]), i,
            angle(i) + f * (angle(i + 1) - angle(i))];
  }
  function shapePath(b, x, y, a) {
    ctx.beginPath();
    if (b.shape === "circle") {
      ctx.arc(X(x), Y(y), Math.max(b.r * scale, 0.5), 0, 2 * Math.PI);
    } else {
      const c = Math.cos(a), s = Math.sin(a);
      for (let k = 0; k < b.v.length; k += 2) {
        const vx = x + c * b.v[k] - s * b.v[k + 1], vy = y + s * b.v[k] + c * b.v[k + 1];
        if (k === 0) ctx.moveTo(X(vx), Y(vy));
        else ctx.lineTo(X(vx), Y(vy));
      }
      if (b.shape === "polygon") ctx.closePath();
    }
  }
  function draw(t) {
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, cssW, cssH);
    ctx.lineJoin = "round";
    for (const b of data.bodies) {
      const [x, y, i, a] = position(b, t);
      if (b.color !== null) {  // the trail so far
        ctx.globalAlpha = 0.5;
        ctx.lineWidth = 1;
        ctx.strokeStyle = b.color;
        ctx.beginPath();
        ctx.moveTo(X(b.p[0]), Y(b.p[1]));
        for (let k = 1; k <= i; ++k) ctx.lineTo(X(b.p[2 * k]), Y(b.p[2 * k + 1]));
        ctx.lineTo(X(x), Y(y));
        ctx.stroke();
      }
      shapePath(b, x, y, a);
      ctx.lineWidth = b.shape === "segment" ? 2.5 : 1.2;
      if (b.shape !== "segment") {
        ctx.globalAlpha = b.color === null ? 1 : 0.35;
        ctx.fillStyle = b.color === null ? data.fixed_fill : b.color;
        ctx.fill();
      }
      ctx.globalAlpha = 1;
      ctx.strokeStyle = b.color === null ? data.fixed_stroke : b.color;
      ctx.stroke();
    }
    ctx.strokeStyle = data.mark_color;
    ctx.lineWidth = 2;
    for (let k = lastAtOrBefore(data.marks, t - flash, 5) + 1; k < data.marks.length / 5; ++k) {
      const m = 5 * k;
      if (data.marks[m] > t) break;
      ctx.globalAlpha = 1 - (t - data.marks[m]) / flash;
      ctx.beginPath();
      ctx.arc(X(data.marks[m + 1]), Y(data.marks[m + 2]), 6, 0, 2 * Math.PI);
      ctx.stroke();
    }
    ctx.globalAlpha = 1;
    clock.textContent = "t = " + t.toPrecision(6) + " s";
    slider.value = end > 0 ? String(Math.round(1000 * t / end)) : "0";
  }

  let t = 0, playing = false, last = null;
  function tick(now) {
    if (!playing) return;
    if (last !== null) t = Math.min(end, t + (now - last) / 1000 * speed);
    last = now;
    draw(t);
    if (t >= end) setPlaying(false);
    else requestAnimationFrame(tick);
  }
  function setPlaying(on) {
    if (on && t >= end) t = 0;
    playing = on;
    last = null;
    button.textContent = on ? "Pause" : "Play";
    if (on) requestAnimationFrame(tick);
  }
  button.addEventListener("click", () => setPlaying(!playing));
  slider.addEventListener("input", () => {
    setPlaying(false);
    t = end * Number(slider.value) / 1000;
    draw(t);
  });
  draw(0);
  setPlaying(end > 0);
})();
)JS";

}  // namespace

std::string html_page(const Run& run, const View& v) {
  const std::string title = xml_escaped(scene_title(run));
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>pge render: {0}</title>\n<link rel=\"icon\" href=\"data:,\">\n<style>\n"
      "body {{ font-family: sans-serif; margin: 1em; color: #222; background: #fafafa; }}\n"
      ".pane {{ display: inline-block; vertical-align: top; margin: 0 1.5em 1.5em 0; }}\n"
      "canvas {{ display: block; background: #fff; border: 1px solid #ccc; }}\n"
      ".controls {{ display: flex; gap: 0.6em; align-items: center; margin: 0.4em 0; }}\n"
      "#pge-time {{ flex: 1; }}\n#pge-clock {{ font-variant-numeric: tabular-nums; min-width: 10em; }}\n"
      "</style>\n</head>\n<body>\n<h1>{0}</h1>\n<p>{1}: {2}</p>\n"
      "<div class=\"pane\">\n<h2>Animation</h2>\n<div class=\"controls\">"
      "<button id=\"pge-play\" type=\"button\">Play</button>"
      "<input id=\"pge-time\" type=\"range\" min=\"0\" max=\"1000\" step=\"1\" value=\"0\" aria-label=\"time\">"
      "<output id=\"pge-clock\"></output></div>\n"
      "<canvas id=\"pge-canvas\" width=\"{3}\" height=\"{4}\"></canvas>\n</div>\n"
      "<div class=\"pane\">\n<h2>Trajectories and collisions</h2>\n{5}</div>\n"
      "<script type=\"application/json\" id=\"pge-data\">{6}</script>\n<script>{7}</script>\n</body>\n</html>\n",
      title, xml_escaped(run.loaded->path), xml_escaped(run_summary(run)), kHtmlWidthPx,
      picture_height_px(v, kHtmlWidthPx), svg_picture(run, v, kHtmlWidthPx), animation_json(run, v), kAnimationScript);
}

}  // namespace pge::cli::render
