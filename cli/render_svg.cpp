// `pge render`, the picture: its frame (world coordinates relative to the extent's corner) and
// the SVG of a run. render_svg() is what `pge report` embeds.
#include "render.hpp"
#include "render_parts.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace pge::cli {
namespace render {
namespace {

namespace fs = std::filesystem;

// Digits after the point that give `digits` significant digits of `scale` (> 0).
int decimals_for(double scale, int digits) {
  return std::clamp(digits - 1 - static_cast<int>(std::floor(std::log10(scale))), 0, 17);
}

std::string moving_color(std::size_t k) {
  return fmt::format("hsl({:.0f},70%,42%)", std::fmod(static_cast<double>(k) * kGoldenAngleDegrees, 360.0));
}

// The element for body `b`'s shape with its reference point at `p` (a turning body: its outline
// `turned`, in world coordinates); `attributes` go inside the tag and `inner` (a <title>) inside
// the element.
std::string shape_element(const BodyDesc& b, Vec2d p, const View& v, std::string_view attributes,
                          std::string_view inner, const std::vector<Vec2d>& turned = {}) {
  std::string head;
  std::string_view tag;
  if (!turned.empty() && b.shape == ShapeKind::Segment) {
    tag = "line";
    head = fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"", v.x(turned[0].x), v.y(turned[0].y),
                       v.x(turned[1].x), v.y(turned[1].y));
  } else if (!turned.empty()) {
    tag = "polygon";
    head = "<polygon points=\"";
    for (std::size_t k = 0; k < turned.size(); ++k) head += (k ? " " : "") + v.point(turned[k]);
    head += '"';
  } else switch (b.shape) {
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

// The width of a glyph of the caption's sans-serif font, on the wide side (DejaVu Sans, the usual
// fallback, averages about 0.55 em), so that a caption laid out with it fits the picture.
constexpr double kGlyphEm = 0.6;

// `text` in lines of at most `chars` characters, broken at spaces (a longer word on its own line).
std::vector<std::string> wrapped(const std::string& text, std::size_t chars) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find(' ', at);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(at, end - at);
    if (!line.empty() && line.size() + 1 + word.size() > chars) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    at = end + 1;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

// The legend: a swatch and a word for each kind of mark, on as many lines of `line` pixels as
// `width` pixels need; y is the first line's baseline, moved to the last's.
std::string legend(double x0, double& y, double font, double line, double width) {
  std::string out;
  double x = x0;
  const double s = font * 0.8;  // swatch size
  auto item = [&](const auto& swatch, std::string_view word) {
    const double advance = s + 14 + font * kGlyphEm * static_cast<double>(word.size());
    if (x > x0 && x + advance - 10 > width - x0) {
      x = x0;
      y += line;
    }
    out += swatch(x, y - s);
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", x + s + 4, y, word);
    x += advance;
  };
  item([&](double left, double top) {
         return fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\" stroke=\"{}\"/>", left,
                            top, s, s, kFixedFill, kFixedStroke);
       },
       "fixed body");
  item([&](double left, double top) {
         return fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\" fill-opacity=\"0.35\" "
                            "stroke=\"{}\"/>",
                            left, top, s, s, moving_color(0), moving_color(0));
       },
       "moving body at the start");
  item([&](double left, double top) {
         return fmt::format("<path d=\"M{:.1f} {:.1f}L{:.1f} {:.1f}L{:.1f} {:.1f}\" fill=\"none\" stroke=\"{}\"/>", left, top + s,
                            left + s / 2, top, left + s, top + s, moving_color(0));
       },
       "trajectory");
  item([&](double left, double top) {
         return fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" stroke=\"{}\" "
                            "stroke-dasharray=\"3 2\"/>",
                            left, top, s, s, moving_color(0));
       },
       "at the end");
  item([&](double left, double top) {
         return fmt::format("<path d=\"M{:.1f} {:.1f}L{:.1f} {:.1f}M{:.1f} {:.1f}L{:.1f} {:.1f}\" stroke=\"{}\" "
                            "stroke-width=\"1.5\"/>",
                            left, top, left + s, top + s, left, top + s, left + s, top, kMarkColor);
       },
       "collision");
  return out;
}

}  // namespace

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
  // The caption, in pixels under the picture: the title, the run's summary and the legend, each
  // wrapped to the width (laid out first: the picture's height depends on it).
  const double x0 = font / 2;
  std::string caption;
  double y = pic_h + line;
  caption += fmt::format("<g class=\"caption\" fill=\"#222\">\n<text x=\"{:.1f}\" y=\"{:.1f}\" font-weight=\"bold\">{}</text>\n",
                         x0, y, xml_escaped(scene_title(run)));
  const auto chars = static_cast<std::size_t>(std::max(20.0, (width_px - 2 * x0) / (font * kGlyphEm)));
  for (const std::string& text : wrapped(run_summary(run), chars)) {
    y += line;
    caption += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", x0, y, xml_escaped(text));
  }
  y += line;
  caption += legend(x0, y, font, line, width_px);
  caption += "</g>\n";
  const int caption_h = static_cast<int>(std::ceil(y - pic_h + font / 2));
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
    out += shape_element(b, b.position, v, attributes, fmt::format("<title>{} (fixed)</title>", xml_escaped(b.id)),
                         turned_outline(run, i, run.paths[i].front()));
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
                         fmt::format("<title>{} at the start</title>", xml_escaped(b.id)),
                         run.paths[i].empty() ? std::vector<Vec2d>{} : turned_outline(run, i, run.paths[i].front()));
  }
  out += "</g>\n";

  out += fmt::format("<g class=\"end\" fill=\"none\" stroke-width=\"{}\" stroke-dasharray=\"{} {}\">\n",
                     v.len(kShapeStrokePx * unit), v.len(kDashPx * unit), v.len(kDashGapPx * unit));
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDesc& b = scene.bodies[i];
    if (b.fixed || run.paths[i].empty()) continue;
    const Sample& last = run.paths[i].back();
    out += shape_element(b, last.p, v, fmt::format("class=\"final\" stroke=\"{}\"", colors[i]),
                         fmt::format("<title>{} at t = {:.9g} s</title>", xml_escaped(b.id), last.t),
                         turned_outline(run, i, last));
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

  out += caption;
  out += "</svg>\n";
  return out;
}

}  // namespace render

std::string render_svg(const LoadedScene& loaded, double until, std::uint64_t max_events, int width_px) {
  if (width_px <= 0) throw std::invalid_argument(fmt::format("render_svg: width must be positive, got {}", width_px));
  WorldOptions wo;
  wo.until = until;
  wo.max_events = max_events;
  wo.solver = SolverKind::Robust;
  wo.frames_per_second = RenderOptions{}.frames;
  const render::Run run = render::simulate(loaded, wo);
  return render::svg_picture(run, render::fit_view(run), width_px);
}

}  // namespace pge::cli
