// The parts of `pge render` (render.hpp): sampling a run (render_sample.cpp), the SVG picture
// with its frame (render_svg.cpp) and the animated HTML page (render_html.cpp); render.cpp is the
// command. Private to cli/.
#pragma once

#include "pge/scene_io.hpp"
#include "pge/world.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace pge::cli::render {

// --- What a picture keeps, and why ----------------------------------------------------------
// Trajectory samples per moving body at most. A long run (snooker: 100,000 collisions) has far
// more corners than a picture can show; past this the samples are thinned evenly (every k-th
// kept, first and last always), so a thinned path is still made of true positions but may cut
// across some bounces.
inline constexpr std::size_t kMaxSamplesPerBody = 2000;
// Samples in all: a 1000-body gas gets 100 per body instead of 2000, which keeps its SVG near
// 2 MB and its HTML page near 5 MB (about 20 bytes per point in the SVG, 30 in the page's data).
inline constexpr std::size_t kMaxSamplesTotal = 100000;
// ... but never fewer than this per body, whatever the body count.
inline constexpr std::size_t kMinSamplesPerBody = 16;
// Collision marks (and the animation's flashes), thinned evenly past this: each mark is about
// 150 bytes of SVG with its tooltip.
inline constexpr std::size_t kMaxMarks = 2000;
// Picture coordinates are written relative to the extent's corner with this many significant
// digits of the picture's size: 1e-6 of it is far below a pixel at any width a page shows, and
// being relative, a scene far from the origin (fixtures/scenes/scale/far-from-origin-1e8.json)
// keeps its detail where absolute coordinates rounded to 6 digits would lose it all.
inline constexpr int kCoordinateDigits = 6;
// Times in the animation data: significant digits of the run's end time.
inline constexpr int kTimeDigits = 7;
// Margin around the extent on every side, a fraction of the extent's larger side.
inline constexpr double kMargin = 0.05;
// The smaller side of the extent is widened to at least this fraction of the larger: a scene
// that is one horizontal wall, or one ball moving along a line, has a zero-height extent.
inline constexpr double kMinAspect = 0.02;
// A picture at most this many times taller than wide; a taller scene is letterboxed in it.
inline constexpr double kMaxHeightRatio = 3;
// Pixel widths: render_command's SVG, and the HTML page's picture and canvas.
inline constexpr int kSvgWidthPx = 800;
inline constexpr int kHtmlWidthPx = 900;
// Line widths and sizes in pixels at the picture's nominal width (they scale with it).
inline constexpr double kShapeStrokePx = 1.2;
inline constexpr double kSegmentStrokePx = 2.5;  // a wall is only its stroke
inline constexpr double kPathStrokePx = 1.0;
inline constexpr double kMarkStrokePx = 1.5;
inline constexpr double kMarkHalfSizePx = 4;
inline constexpr double kDashPx = 5;
inline constexpr double kDashGapPx = 3;
// Colors: fixed bodies grey, collision marks red; moving bodies get hues a golden angle apart,
// so that neighbours in the scene's order never look alike.
inline constexpr const char* kFixedFill = "#d9d9d9";
inline constexpr const char* kFixedStroke = "#7f7f7f";
inline constexpr const char* kMarkColor = "#e00000";
inline constexpr double kGoldenAngleDegrees = 137.50776405003785;

// --- Sampling (render_sample.cpp) -------------------------------------------------------------

// A body's place at t: its reference point (the scene's `position`), or for a rotating body its
// pivot (centroid or midpoint, which moves on the engine's path) and its angle, unwrapped (it
// grows by 2 pi a turn), so that both interpolate exactly between samples where no force acts.
struct Sample {
  double t = 0;
  Vec2d p;
  double angle = 0;
};

struct Mark {
  double t = 0;
  Vec2d p;
  BodyIndex a = kNoBody, b = kNoBody;
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
  // Per body: for a rotating body its vertices about the pivot (World::pivot_vertices; a
  // segment's two ends), drawn turned by each sample's angle about its p; empty for the others,
  // drawn from the scene's shape at their reference point. A fixed spinning body has two
  // samples (start and end: it turns at a constant rate about a fixed pivot).
  std::vector<std::vector<Vec2d>> turning;
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
Run simulate(const LoadedScene& loaded, const WorldOptions& options);

// --- The picture's frame, and the SVG (render_svg.cpp) ----------------------------------------

// `v` with `decimals` digits after the point, trailing zeros dropped ("0.5", "12", never "-0").
std::string fixed(double v, int decimals);

// Body `i`'s outline at sample `s` in world coordinates (a turning body's; empty otherwise).
std::vector<Vec2d> turned_outline(const Run& run, std::size_t i, const Sample& s);

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

View fit_view(const Run& run);
// The picture's pixel height for a pixel width: the box's aspect ratio, within limits.
int picture_height_px(const View& v, int width_px);
// Each body's color ("" for fixed bodies), in scene order.
std::vector<std::string> body_colors(const Scene& scene);
std::string xml_escaped(std::string_view s);
std::string scene_title(const Run& run);
// One line: "N bodies (k moving), solver S, horizon H s; stopped: R at t = T s; M collisions".
std::string run_summary(const Run& run);
// The picture: an <svg> element `width_px` wide (see render_svg.cpp).
std::string svg_picture(const Run& run, const View& v, int width_px);

// --- The HTML page (render_html.cpp) ----------------------------------------------------------

// A self-contained page: the animation on a canvas beside the SVG picture.
std::string html_page(const Run& run, const View& v);

}  // namespace pge::cli::render
