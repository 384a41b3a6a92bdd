#include "render.hpp"

#include "exit_codes.hpp"
#include "scene_files.hpp"
#include "trace.hpp"

#include "pge/scene_io.hpp"
#include "pge/step_loop.hpp"
#include "pge/world.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pge::cli {
namespace {

namespace fs = std::filesystem;

// --- What a picture keeps, and why ----------------------------------------------------------
// Trajectory samples per moving body at most. A long run (snooker: 100,000 collisions) has far
// more corners than a picture can show; past this the samples are thinned evenly (every k-th
// kept, first and last always), so a thinned path is still made of true positions but may cut
// across some bounces.
constexpr std::size_t kMaxSamplesPerBody = 2000;
// Samples in all: a 1000-body gas gets 100 per body instead of 2000, which keeps its SVG near
// 2 MB and its HTML page near 5 MB (about 20 bytes per point in the SVG, 30 in the page's data).
constexpr std::size_t kMaxSamplesTotal = 100000;
// ... but never fewer than this per body, whatever the body count.
constexpr std::size_t kMinSamplesPerBody = 16;
// Collision marks (and the animation's flashes), thinned evenly past this: each mark is about
// 150 bytes of SVG with its tooltip.
constexpr std::size_t kMaxMarks = 2000;
// Picture coordinates are written relative to the extent's corner with this many significant
// digits of the picture's size: 1e-6 of it is far below a pixel at any width a page shows, and
// being relative, a scene far from the origin (fixtures/scenes/scale/far-from-origin-1e8.json)
// keeps its detail where absolute coordinates rounded to 6 digits would lose it all.
constexpr int kCoordinateDigits = 6;
// Times in the animation data: significant digits of the run's end time.
constexpr int kTimeDigits = 7;
// Margin around the extent on every side, a fraction of the extent's larger side.
constexpr double kMargin = 0.05;
// The smaller side of the extent is widened to at least this fraction of the larger: a scene
// that is one horizontal wall, or one ball moving along a line, has a zero-height extent.
constexpr double kMinAspect = 0.02;
// A picture at most this many times taller than wide; a taller scene is letterboxed in it.
constexpr double kMaxHeightRatio = 3;
// Pixel widths: render_command's SVG, and the HTML page's picture and canvas.
constexpr int kSvgWidthPx = 800;
constexpr int kHtmlWidthPx = 900;
// Line widths and sizes in pixels at the picture's nominal width (they scale with it).
constexpr double kShapeStrokePx = 1.2;
constexpr double kSegmentStrokePx = 2.5;  // a wall is only its stroke
constexpr double kPathStrokePx = 1.0;
constexpr double kMarkStrokePx = 1.5;
constexpr double kMarkHalfSizePx = 4;
constexpr double kDashPx = 5;
constexpr double kDashGapPx = 3;
// Colors: fixed bodies grey, collision marks red; moving bodies get hues a golden angle apart,
// so that neighbours in the scene's order never look alike.
constexpr const char* kFixedFill = "#d9d9d9";
constexpr const char* kFixedStroke = "#7f7f7f";
constexpr const char* kMarkColor = "#e00000";
constexpr double kGoldenAngleDegrees = 137.50776405003785;

// --- Sampling ---------------------------------------------------------------------------------

struct Sample {
  double t = 0;
  Vec2d p;
};

struct Mark {
  double t = 0;
  Vec2d p;
  BodyIndex a = kNoBody, b = kNoBody;
};

// Keeps at most `cap` items of a stream of unknown length, evenly spread, in O(cap) memory:
// every stride-th item is kept, and when 2 * cap are kept every other one is dropped and the
// stride doubles. finish() then picks `cap` evenly from those, the first and last item always.
template <class Item> class Thinned {
 public:
  explicit Thinned(std::size_t cap) : cap_(std::max<std::size_t>(cap, 2)) {}

  void add(const Item& item) {
    last_ = item;
    last_kept_ = seen_ % stride_ == 0;
    ++seen_;
    if (!last_kept_) return;
    kept_.push_back(item);
    if (kept_.size() >= 2 * cap_) halve();
  }

  std::uint64_t seen() const { return seen_; }

  std::vector<Item> finish() const {
    std::vector<Item> all = kept_;
    if (seen_ > 0 && !last_kept_) all.push_back(last_);
    if (all.size() <= cap_) return all;
    std::vector<Item> out;
    out.reserve(cap_);
    for (std::size_t k = 0; k < cap_; ++k) out.push_back(all[k * (all.size() - 1) / (cap_ - 1)]);
    return out;
  }

 private:
  void halve() {
    std::size_t j = 0;
    for (std::size_t i = 0; i < kept_.size(); i += 2) kept_[j++] = kept_[i];
    kept_.resize(j);
    stride_ *= 2;
    last_kept_ = false;  // the size was even: the last kept item had an odd index
  }

  std::size_t cap_;
  std::uint64_t stride_ = 1;
  std::uint64_t seen_ = 0;
  std::vector<Item> kept_;
  Item last_{};
  bool last_kept_ = false;
};

struct Box {
  Vec2d lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2d hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};

  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y); }
  void add(Vec2d p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  void add(const Box& local, Vec2d offset) {
    if (local.empty()) return;
    add(local.lo + offset);
    add(local.hi + offset);
  }
};

// The body's shape box relative to its position.
Box shape_box(const BodyDesc& b) {
  Box box;
  switch (b.shape) {
    case ShapeKind::Circle:
      box.add({-b.radius, -b.radius});
      box.add({b.radius, b.radius});
      break;
    case ShapeKind::Segment:
      box.add(b.a);
      box.add(b.b);
      break;
    case ShapeKind::Polygon:
      for (const Vec2d& v : b.vertices) box.add(v);
      break;
  }
  return box;
}

// What one run leaves for the picture.
struct Run {
  const LoadedScene* loaded = nullptr;
  std::string solver;
  double horizon = 0;
  double end = 0;  // the time the run stopped at
  StopReason stop = StopReason::ReachedUntil;
  std::uint64_t collisions = 0;
  StormInfo<double> storm;
  std::vector<std::vector<Sample>> paths;  // per body; a fixed body's is its position alone
  std::vector<Mark> marks;                 // thinned
  std::uint64_t marks_seen = 0;
  Box extent;  // of every shape at every sample, and every contact point

  const Scene& scene() const { return loaded->scene; }
};

// Simulates in double. Samples every moving body at the start, at every frame (`options`'s
// frames_per_second) while it accelerates, at each of its collisions and motion changes (so a
// bounce is a sharp corner), and at the end. On a stretch without acceleration the path is a
// straight line at constant speed, which the corners at its two ends already give exactly
// (linear interpolation in the animation is then exact too): frame samples there would only be
// thinned away again. Throws what World throws.
Run simulate(const LoadedScene& loaded, const WorldOptions& options) {
  const Scene& scene = loaded.scene;
  World<double> world(scene, options);
  const std::size_t n = world.body_count();
  std::vector<BodyIndex> moving;
  for (BodyIndex i = 0; i < n; ++i)
    if (!world.is_fixed(i)) moving.push_back(i);
  const std::size_t cap =
      std::clamp(kMaxSamplesTotal / std::max<std::size_t>(moving.size(), 1), kMinSamplesPerBody, kMaxSamplesPerBody);

  Run run;
  run.loaded = &loaded;
  std::vector<Box> local(n);
  for (BodyIndex i = 0; i < n; ++i) local[i] = shape_box(scene.bodies[i]);
  std::vector<Thinned<Sample>> paths(n, Thinned<Sample>(cap));
  auto sample = [&](BodyIndex i) {
    if (world.is_fixed(i)) return;
    const Vec2d p = world.snapshot(i).position;
    paths[i].add({world.time(), p});
    run.extent.add(local[i], p);
  };
  for (BodyIndex i = 0; i < n; ++i) {
    if (world.is_fixed(i)) run.extent.add(local[i], scene.bodies[i].position);
    sample(i);
  }

  Thinned<Mark> marks(kMaxMarks);
  world.on_collision([&](const CollisionInfo<double>& c) {
    sample(c.a);
    sample(c.b);
    if (c.impulse > 0) {  // a graze (predicted, not approaching) applies nothing: no mark
      marks.add({c.time, c.point, c.a, c.b});
      run.extent.add(c.point);
    }
  });
  world.on_motion_change([&](BodyIndex i, double) { sample(i); });
  world.on_frame([&](const World<double>& w, double) {
    for (const BodyIndex i : moving)
      if (!(w.motion(i).acc == Vec2d{})) sample(i);
  });
  step_to_end(world);
  for (const BodyIndex i : moving) sample(i);

  run.solver = std::string(solver_name(world.solver()));
  run.horizon = world.horizon();
  run.end = world.time();
  run.stop = world.stop_reason();
  run.collisions = world.counts().collisions;
  run.storm = world.storm();
  run.paths.resize(n);
  for (BodyIndex i = 0; i < n; ++i)
    run.paths[i] = world.is_fixed(i) ? std::vector<Sample>{{0, scene.bodies[i].position}} : paths[i].finish();
  run.marks = marks.finish();
  run.marks_seen = marks.seen();
  return run;
}

// --- Number formatting and the picture's frame ------------------------------------------------

// `v` with `decimals` digits after the point, trailing zeros dropped ("0.5", "12", never "-0").
std::string fixed(double v, int decimals) {
  std::string s = fmt::format("{:.{}f}", v, decimals);
  if (s.find('.') != std::string::npos) {
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

// Digits after the point that give `digits` significant digits of `scale` (> 0).
int decimals_for(double scale, int digits) {
  return std::clamp(digits - 1 - static_cast<int>(std::floor(std::log10(scale))), 0, 17);
}

// The picture's frame: world coordinates minus `origin`, the extent's (widened) corner, so that
// the extent is [0, width] x [0, height]; y up (the SVG flips it with a transform).
struct View {
  Vec2d origin;
  double width = 1, height = 1;
  double margin = 0;
  int decimals = 6;       // of coordinates and lengths
  int time_decimals = 6;  // of times

  double span() const { return std::max(width, height); }
  double box_width() const { return width + 2 * margin; }
  double box_height() const { return height + 2 * margin; }
  std::string x(double wx) const { return fixed(wx - origin.x, decimals); }
  std::string y(double wy) const { return fixed(wy - origin.y, decimals); }
  std::string len(double d) const { return fixed(d, decimals); }
  std::string t(double t) const { return fixed(t, time_decimals); }
  std::string point(Vec2d p) const { return x(p.x) + "," + y(p.y); }
};

View fit_view(const Run& run) {
  Box e = run.extent;
  if (e.empty()) e.add({0, 0});  // a scene without bodies
  View v;
  v.origin = e.lo;
  double w = e.hi.x - e.lo.x, h = e.hi.y - e.lo.y;
  double span = std::max(w, h);
  if (!(span > 0)) {  // one point (no bodies): a unit square around it
    span = w = h = 1;
    v.origin -= Vec2d{0.5, 0.5};
  }
  const double min_side = kMinAspect * span;
  if (w < min_side) {
    v.origin.x -= (min_side - w) / 2;
    w = min_side;
  }
  if (h < min_side) {
    v.origin.y -= (min_side - h) / 2;
    h = min_side;
  }
  v.width = w;
  v.height = h;
  v.margin = kMargin * span;
  v.decimals = decimals_for(v.span() + 2 * v.margin, kCoordinateDigits);
  v.time_decimals = run.end > 0 ? decimals_for(run.end, kTimeDigits) : kTimeDigits;
  return v;
}

// The picture's pixel height for a pixel width: the box's aspect ratio, within limits.
int picture_height_px(const View& v, int width_px) {
  const double h = width_px * v.box_height() / v.box_width();
  return static_cast<int>(std::lround(std::clamp(h, 1.0, kMaxHeightRatio * width_px)));
}

std::string moving_color(std::size_t k) {
  return fmt::format("hsl({:.0f},70%,42%)", std::fmod(static_cast<double>(k) * kGoldenAngleDegrees, 360.0));
}

// Each body's color ("" for fixed bodies), in scene order.
std::vector<std::string> body_colors(const Scene& scene) {
  std::vector<std::string> colors;
  std::size_t k = 0;
  for (const BodyDesc& b : scene.bodies) colors.push_back(b.fixed ? std::string() : moving_color(k++));
  return colors;
}

std::string xml_escaped(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // XML 1.0 has no way to write other control characters, even escaped.
        out += static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n' ? '?' : ch;
    }
  }
  return out;
}

std::string scene_title(const Run& run) {
  return run.scene().name.empty() ? fs::path(run.loaded->path).stem().string() : run.scene().name;
}

// One line: "N bodies (k moving), solver S, horizon H s; stopped: R at t = T s; M collisions".
std::string run_summary(const Run& run) {
  const Scene& s = run.scene();
  const auto moving = std::count_if(s.bodies.begin(), s.bodies.end(), [](const BodyDesc& b) { return !b.fixed; });
  std::string marked;
  if (run.marks.size() < run.marks_seen) marked = fmt::format(" ({} marked)", run.marks.size());
  return fmt::format("{} bodies ({} moving), solver {}, horizon {:.6g} s; stopped: {} at t = {:.9g} s; {} collisions{}",
                     s.bodies.size(), moving, run.solver, run.horizon, stop_reason_name(run.stop), run.end,
                     run.collisions, marked);
}

// --- SVG ----------------------------------------------------------------------------------------

// The element for body `b`'s shape with its reference point at `p`; `attributes` go inside the
// tag and `inner` (a <title>) inside the element.
std::string shape_element(const BodyDesc& b, Vec2d p, const View& v, std::string_view attributes,
                          std::string_view inner) {
  std::string head;
  std::string_view tag;
  switch (b.shape) {
    case ShapeKind::Circle:
      tag = "circle";
      head = fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\"", v.x(p.x), v.y(p.y), v.len(b.radius));
      break;
    case ShapeKind::Segment:
      tag = "line";
      head = fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"", v.x(p.x + b.a.x), v.y(p.y + b.a.y),
                         v.x(p.x + b.b.x), v.y(p.y + b.b.y));
      break;
    case ShapeKind::Polygon: {
      tag = "polygon";
      head = "<polygon points=\"";
      for (std::size_t k = 0; k < b.vertices.size(); ++k) head += (k ? " " : "") + v.point(p + b.vertices[k]);
      head += '"';
      break;
    }
  }
  head += fmt::format(" {}", attributes);
  if (inner.empty()) return head + "/>\n";
  return fmt::format("{}>{}</{}>\n", head, inner, tag);
}

// The points of a polyline through `samples`, repeated points (after rounding) left out.
std::string polyline_points(const std::vector<Sample>& samples, const View& v) {
  std::string out, last;
  for (const Sample& s : samples) {
    std::string p = v.point(s.p);
    if (p == last) continue;
    if (!out.empty()) out += ' ';
    out += p;
    last = std::move(p);
  }
  return out;
}

// The legend line: a swatch and a word for each kind of mark.
std::string legend(double x0, double y, double font) {
  std::string out;
  double x = x0;
  const double s = font * 0.8;  // swatch size
  auto item = [&](const std::string& swatch, std::string_view word) {
    out += swatch;
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", x + s + 4, y, word);
    x += s + 14 + font * 0.52 * static_cast<double>(word.size());
  };
  const double top = y - s;
  item(fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\" stroke=\"{}\"/>", x, top,
                   s, s, kFixedFill, kFixedStroke),
       "fixed body");
  item(fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\" fill-opacity=\"0.35\" "
                   "stroke=\"{}\"/>",
                   x, top, s, s, moving_color(0), moving_color(0)),
       "moving body at the start");
  item(fmt::format("<path d=\"M{:.1f} {:.1f}L{:.1f} {:.1f}L{:.1f} {:.1f}\" fill=\"none\" stroke=\"{}\"/>", x, y,
                   x + s / 2, top, x + s, y, moving_color(0)),
       "trajectory");
  item(fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" stroke=\"{}\" "
                   "stroke-dasharray=\"3 2\"/>",
                   x, top, s, s, moving_color(0)),
       "at the end");
  item(fmt::format("<path d=\"M{:.1f} {:.1f}L{:.1f} {:.1f}M{:.1f} {:.1f}L{:.1f} {:.1f}\" stroke=\"{}\" "
                   "stroke-width=\"1.5\"/>",
                   x, top, x + s, y, x, y, x + s, top, kMarkColor),
       "collision");
  return out;
}

// The picture: an <svg> element `width_px` wide, the scene drawn in a nested <svg> in world
// coordinates (y flipped up), the caption and legend below it in pixels. Presentation
// attributes only, no <style>: the element is embedded in other pages (`pge report`), where a
// style sheet would leak into the page.
std::string svg_picture(const Run& run, const View& v, int width_px) {
  const Scene& scene = run.scene();
  const std::vector<std::string> colors = body_colors(scene);
  const int pic_h = picture_height_px(v, width_px);
  const double font = std::clamp(width_px / 60.0, 9.0, 13.0);
  const double line = 1.5 * font;
  const int caption_h = static_cast<int>(std::ceil(3 * line + font / 2));
  // World units per pixel: the nested svg scales the box to fit (meet) the picture's pixels.
  const double unit = 1 / std::min(width_px / v.box_width(), pic_h / v.box_height());
  const std::string title = xml_escaped(scene_title(run));

  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"pge-render\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"{2:.1f}\">\n"
      "<title>{3}</title>\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      width_px, pic_h + caption_h, font, title);
  // The box in picture coordinates is [-margin, width + margin] x [-margin, height + margin];
  // flipped, y runs from -(height + margin) to margin.
  out += fmt::format(
      "<svg class=\"scene\" x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" viewBox=\"{} {} {} {}\" "
      "preserveAspectRatio=\"xMidYMid meet\">\n<g transform=\"scale(1,-1)\">\n",
      width_px, pic_h, v.len(-v.margin), v.len(-(v.height + v.margin)), v.len(v.box_width()), v.len(v.box_height()));

  // Fixed bodies first (under everything), then trajectories, start shapes, end shapes, marks.
  out += fmt::format("<g class=\"fixed-bodies\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\">\n", kFixedFill,
                     kFixedStroke, v.len(kShapeStrokePx * unit));
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    if (!b.fixed) continue;
    const std::string attributes = b.shape == ShapeKind::Segment
                                       ? fmt::format("class=\"body fixed\" stroke-width=\"{}\"", v.len(kSegmentStrokePx * unit))
                                       : std::string("class=\"body fixed\"");
    out += shape_element(b, b.position, v, attributes, fmt::format("<title>{} (fixed)</title>", xml_escaped(b.id)));
  }
  out += "</g>\n";

  out += fmt::format("<g class=\"trajectories\" fill=\"none\" stroke-width=\"{}\" stroke-opacity=\"0.8\" "
                     "stroke-linejoin=\"round\">\n",
                     v.len(kPathStrokePx * unit));
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].fixed) continue;
    const std::string points = polyline_points(run.paths[i], v);
    if (points.find(' ') == std::string::npos) continue;  // it never moved
    out += fmt::format("<polyline class=\"path\" stroke=\"{}\" points=\"{}\"/>\n", colors[i], points);
  }
  out += "</g>\n";

  out += fmt::format("<g class=\"start\" fill-opacity=\"0.35\" stroke-width=\"{}\">\n", v.len(kShapeStrokePx * unit));
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    if (b.fixed) continue;
    const double width = b.shape == ShapeKind::Segment ? kSegmentStrokePx : kShapeStrokePx;
    out += shape_element(b, b.position, v,
                         fmt::format("class=\"body\" fill=\"{0}\" stroke=\"{0}\" stroke-width=\"{1}\"", colors[i],
                                     v.len(width * unit)),
                         fmt::format("<title>{} at the start</title>", xml_escaped(b.id)));
  }
  out += "</g>\n";

  out += fmt::format("<g class=\"end\" fill=\"none\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\">\n",
                     v.len(kShapeStrokePx * unit), v.len(kDashPx * unit), v.len(kDashGapPx * unit));
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    if (b.fixed || run.paths[i].empty()) continue;
    const Sample& last = run.paths[i].back();
    out += shape_element(b, last.p, v, fmt::format("class=\"final\" stroke=\"{}\"", colors[i]),
                         fmt::format("<title>{} at t = {:.9g} s</title>", xml_escaped(b.id), last.t));
  }
  out += "</g>\n";

  const double m = kMarkHalfSizePx * unit;
  out += fmt::format("<g class=\"collisions\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\">\n", kMarkColor,
                     v.len(kMarkStrokePx * unit));
  for (const Mark& k : run.marks) {
    out += fmt::format("<path class=\"hit\" d=\"M{0} {1}L{2} {3}M{0} {3}L{2} {1}\"><title>t = {4:.9g} s: {5} and {6} "
                       "at ({7:.9g}, {8:.9g})</title></path>\n",
                       v.x(k.p.x - m), v.y(k.p.y - m), v.x(k.p.x + m), v.y(k.p.y + m), k.t,
                       xml_escaped(scene.bodies[k.a].id), xml_escaped(scene.bodies[k.b].id), k.p.x, k.p.y);
  }
  out += "</g>\n</g>\n</svg>\n";

  // The caption, in pixels under the picture.
  const double x0 = font / 2;
  double y = pic_h + line;
  out += fmt::format("<g class=\"caption\" fill=\"#222\">\n<text x=\"{:.1f}\" y=\"{:.1f}\" font-weight=\"bold\">{}</text>\n",
                     x0, y, title);
  y += line;
  out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", x0, y, xml_escaped(run_summary(run)));
  y += line;
  out += legend(x0, y, font);
  out += "</g>\n</svg>\n";
  return out;
}

// --- HTML ---------------------------------------------------------------------------------------

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
        out += fmt::format("\"shape\":\"segment\",\"v\":[{},{},{},{}]", v.len(b.a.x), v.len(b.a.y), v.len(b.b.x),
                           v.len(b.b.y));
        break;
      case ShapeKind::Polygon:
        out += "\"shape\":\"polygon\",\"v\":[";
        for (std::size_t k = 0; k < b.vertices.size(); ++k)
          out += fmt::format("{}{},{}", k ? "," : "", v.len(b.vertices[k].x), v.len(b.vertices[k].y));
        out += ']';
        break;
    }
    std::string times, points;
    for (const Sample& s : run.paths[i]) {
      times += (times.empty() ? "" : ",") + v.t(s.t);
      points += (points.empty() ? "" : ",") + v.x(s.p.x) + "," + v.y(s.p.y);
    }
    out += fmt::format(",\"t\":[{}],\"p\":[{}]}}", times, points);
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
  function position(b, t) {
    const i = lastAtOrBefore(b.t, t, 1);
    if (i < 0) return [b.p[0], b.p[1], 0];
    if (i + 1 >= b.t.length) return [b.p[2 * i], b.p[2 * i + 1], i];
    const t0 = b.t[i], t1 = b.t[i + 1];
    const f = t1 > t0 ? (t - t0) / (t1 - t0) : 1;
    return [b.p[2 * i] + f * (b.p[2 * i + 2] - b.p[2 * i]), b.p[2 * i + 1] + f * (b.p[2 * i + 3] - b.p[2 * i + 1]), i];
  }
  function shapePath(b, x, y) {
    ctx.beginPath();
    if (b.shape === "circle") {
      ctx.arc(X(x), Y(y), Math.max(b.r * scale, 0.5), 0, 2 * Math.PI);
    } else {
      for (let k = 0; k < b.v.length; k += 2) {
        if (k === 0) ctx.moveTo(X(x + b.v[k]), Y(y + b.v[k + 1]));
        else ctx.lineTo(X(x + b.v[k]), Y(y + b.v[k + 1]));
      }
      if (b.shape === "polygon") ctx.closePath();
    }
  }
  function draw(t) {
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, cssW, cssH);
    ctx.lineJoin = "round";
    for (const b of data.bodies) {
      const [x, y, i] = position(b, t);
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
      shapePath(b, x, y);
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

// --- The command --------------------------------------------------------------------------------

enum class Form { Svg, Html };

std::optional<Form> form_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".svg") return Form::Svg;
  if (ext == ".html") return Form::Html;
  return std::nullopt;
}

// Writes `text` to `path`; "" or what went wrong.
std::string write_file(const std::string& path, const std::string& text) {
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (out) out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (out) out.close();
  if (out) return {};
  return errno ? std::strerror(errno) : "write failed";
}

}  // namespace

std::string render_svg(const LoadedScene& loaded, double until, std::uint64_t max_events, int width_px) {
  if (width_px <= 0) throw std::invalid_argument(fmt::format("render_svg: width must be positive, got {}", width_px));
  WorldOptions wo;
  wo.until = until;
  wo.max_events = max_events;
  wo.solver = SolverKind::Robust;
  wo.frames_per_second = RenderOptions{}.frames;
  const Run run = simulate(loaded, wo);
  return svg_picture(run, fit_view(run), width_px);
}

int render_command(const RenderOptions& options) {
  const std::optional<Form> form = form_of(options.out);
  if (!form) {
    fmt::print(stderr, "pge render: the output file must end in .svg (a picture) or .html (an animation), got \"{}\"\n",
               options.out);
    return kExitUsage;
  }
  if (!(options.frames > 0) || !std::isfinite(options.frames)) {
    fmt::print(stderr, "pge render: --frames must be a positive number of samples per second, got {}\n", options.frames);
    return kExitUsage;
  }
  WorldOptions wo;
  wo.until = options.until;
  wo.max_events = options.max_events;
  wo.frames_per_second = options.frames;
  if (!options.solver.empty()) {
    SolverKind kind{};
    if (!parse_solver_kind(options.solver, kind)) {
      fmt::print(stderr, "pge render: unknown solver \"{}\" (fast, robust, certified)\n", options.solver);
      return kExitUsage;
    }
    wo.solver = kind;
  }

  // A missing directory is found before a long simulation, not after it.
  std::error_code ec;
  if (const fs::path dir = fs::path(options.out).parent_path(); !dir.empty() && !fs::is_directory(dir, ec)) {
    fmt::print(stderr, "pge render: cannot write {}: no such directory {}\n", options.out, dir.string());
    return kExitOutput;
  }

  const std::optional<LoadedScene> loaded = load_scene("render", options.scene);
  if (!loaded) return kExitBadScene;
  Run run;
  if (const int refused = simulate_scene("render", options.scene, [&] { run = simulate(*loaded, wo); });
      refused != kExitOk)
    return refused;

  const View view = fit_view(run);
  const std::string text = *form == Form::Svg
                               ? "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + svg_picture(run, view, kSvgWidthPx)
                               : html_page(run, view);
  if (const std::string error = write_file(options.out, text); !error.empty()) {
    fmt::print(stderr, "pge render: cannot write {}: {}\n", options.out, error);
    return kExitOutput;
  }
  if (!options.quiet) {
    fmt::print("render: {} -> {}: {} bodies, {} collisions, t = {:.9g} ({}){}\n", options.scene, options.out,
               run.scene().bodies.size(), run.collisions, run.end, run.solver,
               run.stop == StopReason::ReachedUntil ? "" : fmt::format(", stopped: {}", stop_reason_name(run.stop)));
  }
  if (run.stop == StopReason::EventStorm) {
    const auto name = [&](BodyIndex i) { return i < run.scene().bodies.size() ? run.scene().bodies[i].id : "?"; };
    fmt::print(stderr,
               "pge render: {}: event storm at t = {:.17g}: bodies \"{}\" and \"{}\", {} collisions; run stopped, "
               "{} shows the run up to there\n",
               options.scene, run.storm.time, name(run.storm.a), name(run.storm.b), run.storm.collisions, options.out);
    return kExitStorm;
  }
  return kExitOk;
}

}  // namespace pge::cli
