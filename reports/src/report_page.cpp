#include "pge/report_page.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace pge::report {
namespace {

namespace fs = std::filesystem;

// Where a zero error sits on a logarithmic axis: below every binary128 rounding error (2^-113
// relative is about 1e-34), so "exact" is a floor of its own.
constexpr double kZeroOnLog = 1e-40;

double on_log(double x) { return x > 0 && std::isfinite(x) ? std::max(x, kZeroOnLog) : kZeroOnLog; }

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw ReportError("cannot write " + path.string());
}

std::string base64(const std::string& data) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((data.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < data.size(); i += 3) {
    const auto byte = [&](std::size_t k) { return k < data.size() ? static_cast<unsigned char>(data[k]) : 0u; };
    const unsigned v = (byte(i) << 16) | (byte(i + 1) << 8) | byte(i + 2);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < data.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < data.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

std::string html_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// A gnuplot string literal (single quotes; a quote is doubled).
std::string gp_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string g(double x) { return fmt::format("{:.4g}", x); }

const char* kTerminal =
    "set terminal svg size 900,540 dynamic enhanced font 'Helvetica,12' background rgb 'white'\n"
    "set grid lc rgb '#dddddd'\nset key outside right top font ',10'\n";

// Colours by solver, dash by scalar: a configuration reads the same on every plot.
std::string style_of(const std::string& solver, const std::string& scalar) {
  const char* colour = solver == "fast" ? "#d62728" : solver == "robust" ? "#1f77b4" : solver == "certified" ? "#2ca02c" : "#7f7f7f";
  const int dash = scalar == "float" ? 2 : scalar == "double" ? 1 : scalar == "long-double" ? 4 : 5;
  return fmt::format("lc rgb '{}' dt {} lw 2", colour, dash);
}

// ---- point labels that never overlap

// A label of a point in data coordinates (empty text: a point with no label, still in the way).
struct PointLabel {
  double x = 0, y = 0;
  std::string text;
};

// A log-log plot with its frame fixed in the 900 x 540 picture (kTerminal's size): decades
// x_lo..x_hi and y_lo..y_hi, margins at fixed fractions of the picture, so that a data point's
// pixel is known before gnuplot draws it.
struct LogFrame {
  int x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;
  static constexpr double kWidth = 900, kHeight = 540;
  static constexpr double kLeft = 0.11, kRight = 0.79, kBottom = 0.14, kTop = 0.91;  // fractions of the picture

  // Pixels, y down (as in the SVG).
  double px(double x) const {
    return kWidth * (kLeft + (kRight - kLeft) * (std::log10(x) - x_lo) / (x_hi - x_lo));
  }
  double py(double y) const {
    return kHeight * (1 - (kBottom + (kTop - kBottom) * (std::log10(y) - y_lo) / (y_hi - y_lo)));
  }
  // The gnuplot commands that fix the frame (logscale xy, ranges, margins), and those that undo them.
  std::string fixed() const {
    return fmt::format("set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\nset xrange [1e{}:1e{}]\n"
                       "set yrange [1e{}:1e{}]\nset lmargin at screen {}\nset rmargin at screen {}\n"
                       "set bmargin at screen {}\nset tmargin at screen {}\n",
                       x_lo, x_hi, y_lo, y_hi, kLeft, kRight, kBottom, kTop);
  }
  static constexpr const char* kUnfixed =
      "unset logscale\nunset format\nunset label\nunset arrow\nset xrange [*:*]\nset yrange [*:*]\n"
      "set lmargin\nset rmargin\nset tmargin\nset bmargin\n";
};

// The whole decades around the positive values, with `room` decades at least at either end.
std::pair<int, int> decades(const std::vector<double>& values, double room = 0.15) {
  double lo = INFINITY, hi = -INFINITY;
  for (const double v : values)
    if (v > 0 && std::isfinite(v)) lo = std::min(lo, std::log10(v)), hi = std::max(hi, std::log10(v));
  if (!(lo <= hi)) lo = hi = 0;
  const int from = static_cast<int>(std::floor(lo - room));
  return {from, std::max(static_cast<int>(std::ceil(hi + room)), from + 1)};
}

struct Box {
  double x0, y0, x1, y1;
  bool meets(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// gnuplot `set label` and `set arrow` commands placing each label near its point where its box
// (estimated from the font: an average glyph of a sans-serif font is about 0.55 em wide; 0.62
// leaves room) meets no other label, no point and not the frame: beside the point first, then on
// rings further out, joined to the point by a thin leader line. Labels go in order of x, so that
// a row of close points fans out to one side. point: the half-size of a point's marker, pixels.
std::string place_labels(std::vector<PointLabel> labels, const LogFrame& f, double point = 7) {
  constexpr double kFont = 8, kGlyph = 0.62 * kFont, kLine = 1.3 * kFont, kPad = 1.5;
  std::stable_sort(labels.begin(), labels.end(), [](const PointLabel& a, const PointLabel& b) { return a.x < b.x; });
  const Box inside{f.px(std::pow(10.0, f.x_lo)) + 2, f.py(std::pow(10.0, f.y_hi)) + 2, f.px(std::pow(10.0, f.x_hi)) - 2,
                   f.py(std::pow(10.0, f.y_lo)) - 2};
  std::vector<Box> taken;
  for (const PointLabel& l : labels)
    taken.push_back({f.px(l.x) - point, f.py(l.y) - point, f.px(l.x) + point, f.py(l.y) + point});
  std::string out;
  const auto screen = [&](double x, double y) {
    return fmt::format("screen {:.5f}, screen {:.5f}", x / LogFrame::kWidth, 1 - y / LogFrame::kHeight);
  };
  for (const PointLabel& l : labels) {
    if (l.text.empty()) continue;
    const double x = f.px(l.x), y = f.py(l.y), w = kGlyph * static_cast<double>(l.text.size());
    // Candidate anchors (the label's left end, its vertical middle), nearest first.
    const double near = point + 2;
    std::vector<std::pair<double, double>> at{{x + near, y},          {x + near - 3, y - near - 4}, {x + near - 3, y + near + 4},
                                              {x - near - w, y},      {x - w / 2, y - near - 7},    {x - w / 2, y + near + 7}};
    for (int ring = 2; ring <= 12; ++ring)
      for (int k = 0; k < 16; ++k) {
        const double angle = -M_PI / 2 + 2 * M_PI * k / 16, r = 12.0 * ring;
        const double cx = x + r * std::cos(angle) * 1.6, cy = y + r * std::sin(angle);
        at.emplace_back(std::cos(angle) >= 0 ? cx : cx - w, cy);
      }
    bool placed = false;
    for (std::size_t c = 0; c < at.size() && !placed; ++c) {
      const auto [ax, ay] = at[c];
      const Box box{ax - kPad, ay - kLine / 2 - kPad, ax + w + kPad, ay + kLine / 2 + kPad};
      if (box.x0 < inside.x0 || box.x1 > inside.x1 || box.y0 < inside.y0 || box.y1 > inside.y1) continue;
      if (std::any_of(taken.begin(), taken.end(), [&](const Box& t) { return t.meets(box); })) continue;
      taken.push_back(box);
      placed = true;
      out += fmt::format("set label {} at {} left font ',{}' noenhanced front\n", gp_quoted(l.text), screen(ax, ay), kFont);
      if (c >= 6) {  // far from its point: a leader line to the label's nearer end
        const double ex = ax > x ? ax - 1 : ax + w + 1;
        out += fmt::format("set arrow from {} to {} nohead lw 0.6 lc rgb '#888888' back\n", screen(x, y), screen(ex, ay));
      }
    }
    // No room anywhere: the table beside the chart names every setting; leave the point unnamed.
  }
  return out;
}

struct Plots {
  std::string script;
  std::vector<std::string> files;  // the SVGs the script writes
};

Plots make_plots(const Results& r, const std::vector<ConfigSummary>& configs, const fs::path& dir) {
  Plots p;
  std::string& s = p.script;
  // Speed against error: one point per configuration, the Pareto front joined.
  if (!configs.empty()) {
    std::string points, front, failing;
    std::vector<const ConfigSummary*> pareto;
    std::vector<PointLabel> labels;
    std::vector<double> xs, ys;
    for (const ConfigSummary& c : configs) {
      if (c.events == 0 || c.wall_seconds <= 0) continue;
      const double ns = 1e9 * c.wall_seconds / static_cast<double>(c.events);
      const std::string line = fmt::format("{} {} \"{}/{}\"\n", g(ns), g(on_log(c.rel_p99)), c.solver, c.scalar);
      labels.push_back({ns, on_log(c.rel_p99), c.solver + "/" + c.scalar});
      xs.push_back(ns);
      ys.push_back(on_log(c.rel_p99));
      points += line;
      if (c.misses + c.phantoms > 0) failing += line;
      if (c.pareto) pareto.push_back(&c);
    }
    std::sort(pareto.begin(), pareto.end(),
              [](const ConfigSummary* a, const ConfigSummary* b) { return a->wall_seconds < b->wall_seconds; });
    for (const ConfigSummary* c : pareto)
      front += fmt::format("{} {}\n", g(1e9 * c->wall_seconds / static_cast<double>(c->events)), g(on_log(c->rel_p99)));
    if (!points.empty()) {
      write_file(dir / "speed_error.dat", points);
      write_file(dir / "pareto.dat", front.empty() ? points.substr(0, points.find('\n') + 1) : front);
      // Labels placed as on the peers chart (place_labels): a solver's scalars can sit close.
      const auto [x_lo, x_hi] = decades(xs);
      const auto [y_lo, y_hi] = decades(ys, 0.5);
      const LogFrame frame{x_lo, x_hi, y_lo, y_hi};
      s += kTerminal;
      s += "set output 'speed_error.svg'\n" + frame.fixed() + place_labels(labels, frame, 12) +
           "set xlabel 'time per event, ns (engine alone, median of repeats; log)'\n"
           "set ylabel 'p99 relative time error (log; exact at 1e-40)'\n"
           "set title 'Speed against error: one point per solver x scalar'\n"
           "plot 'pareto.dat' using 1:2 with linespoints lw 2 pt 6 ps 2.4 lc rgb '#ff7f0e' title 'Pareto front', \\\n"
           "     'speed_error.dat' using 1:2 with points pt 7 ps 1.3 lc rgb '#1f77b4' title 'configuration'";
      if (!failing.empty()) {
        write_file(dir / "speed_error_miss.dat", failing);
        s += ", \\\n     'speed_error_miss.dat' using 1:2 with points pt 2 ps 2.2 lc rgb 'black' title 'misses or phantoms'";
      }
      s += "\nunset title\n";
      s += LogFrame::kUnfixed;
      p.files.push_back("speed_error.svg");
    }
  }
  // Error CDFs from the histograms.
  {
    std::string plot;
    int block = 0;
    std::string data;
    for (const ConfigSummary& c : configs) {
      std::uint64_t total = 0;
      for (std::uint64_t n : c.rel_hist) total += n;
      if (total == 0) continue;
      std::uint64_t sum = 0;
      for (std::size_t b = 0; b < c.rel_hist.size(); ++b) {
        if (c.rel_hist[b] == 0 && sum == 0) continue;
        sum += c.rel_hist[b];
        data += fmt::format("{} {}\n", g(on_log(rel_bucket_upper(static_cast<int>(b)))),
                            g(static_cast<double>(sum) / static_cast<double>(total)));
        if (sum == total) break;
      }
      data += "\n\n";
      plot += fmt::format("{}'error_cdf.dat' index {} using 1:2 with steps {} title '{}/{}'", plot.empty() ? "" : ", \\\n  ",
                          block++, style_of(c.solver, c.scalar), c.solver, c.scalar);
    }
    if (!plot.empty()) {
      write_file(dir / "error_cdf.dat", data);
      s += kTerminal;
      s += "set output 'error_cdf.svg'\nset logscale x\nset format x '10^{%L}'\nset yrange [0:1.02]\n"
           "set xlabel 'relative time error of an event, upper bound of its binary bucket (log; exact at 1e-40)'\n"
           "set ylabel 'fraction of judged events'\nset title 'Error CDFs, every judged event'\n"
           "plot " + plot + "\nunset title\nunset logscale\nunset format\nset autoscale y\n";
      p.files.push_back("error_cdf.svg");
    }
  }
  // Peers: PGE in every configuration and Box2D and Chipmunk at each setting, on the pge compare scenes.
  {
    struct Point {
      double wall = 0, drift = 0;
      std::uint64_t tunnelled = 0;
      int scenes = 0;
      std::string engine;
    };
    std::map<std::string, Point> points;  // by engine/setting
    for (const Row& x : r.rows) {
      if (x.kind != RowKind::Peer || !x.error.empty()) continue;
      Point& point = points[x.config()];
      point.engine = x.solver;
      point.wall += x.wall_seconds;
      if (x.elastic) point.drift = std::max(point.drift, std::abs(x.energy_drift));
      point.tunnelled += x.tunnelled;
      ++point.scenes;
    }
    // One series per peer and one per PGE solver (its scalars are told apart by their drift, each
    // about its unit roundoff: robust's points carry the scalar's name); short labels, since the
    // table beside the chart has every setting in full.
    struct Series {
      std::string data, title, style;
      std::vector<PointLabel> labels;
    };
    std::map<std::string, Series> series;  // by file stem, in plot order
    std::string tunnelling;
    for (const auto& [config, point] : points) {
      const std::string setting = config.substr(point.engine.size() + 1);  // "robust/double", "60 Hz, 8+3 iterations"
      std::string stem, label;
      if (point.engine == "pge") {
        const std::string solver = setting.substr(0, setting.find('/'));
        stem = "pge_" + solver;
        label = solver == "robust" ? setting.substr(solver.size() + 1) : "";
        series[stem].title = "PGE " + solver;  // triangles fast, discs robust, squares certified
        series[stem].style = fmt::format("pt {} ps 1.3 lc rgb '#1f77b4'", solver == "fast" ? 9 : solver == "robust" ? 7 : 5);
      } else {
        stem = point.engine;
        label = setting;
        for (const std::string cut : {" iterations", ","})
          if (const auto at = label.find(cut); at != std::string::npos) label.erase(at, cut.size());
        series[stem].title = point.engine == "box2d" ? "Box2D" : point.engine == "chipmunk" ? "Chipmunk" : point.engine;
        series[stem].style = fmt::format("pt 7 ps 1.3 lc rgb '{}'", point.engine == "box2d" ? "#ff7f0e" : "#2ca02c");
      }
      series[stem].data += fmt::format("{} {}\n", g(point.wall), g(on_log(point.drift)));
      series[stem].labels.push_back({point.wall, on_log(point.drift), label});
      if (point.tunnelled > 0) tunnelling += fmt::format("{} {}\n", g(point.wall), g(on_log(point.drift)));
    }
    if (!series.empty()) {
      // The frame is fixed (margins and ranges), so that the labels can be placed here, each
      // where it overlaps no other label and no point (gnuplot's `with labels` puts every label at
      // the same offset from its point, and a dozen settings of nearly the same speed and drift
      // wrote over one another).
      std::vector<PointLabel> all;
      std::vector<double> walls;
      for (const auto& [stem, one] : series)
        for (const PointLabel& l : one.labels) {
          all.push_back(l);
          walls.push_back(l.x);
        }
      const auto [x_lo, x_hi] = decades(walls);
      const LogFrame frame{x_lo, x_hi, -42, 1};
      std::string plot;
      for (const auto& [stem, one] : series) {
        write_file(dir / ("peers_" + stem + ".dat"), one.data);
        plot += fmt::format("{}'peers_{}.dat' using 1:2 with points {} title '{}'", plot.empty() ? "" : ", \\\n  ", stem,
                            one.style, one.title);
      }
      if (!tunnelling.empty()) {
        write_file(dir / "peers_tunnelling.dat", tunnelling);
        plot += ", \\\n  'peers_tunnelling.dat' using 1:2 with points pt 2 ps 2.2 lc rgb 'black' title 'a body tunnelled'";
      }
      s += kTerminal;
      s += "set output 'peers.svg'\n" + frame.fixed() + place_labels(all, frame);
      s += "set xlabel 'wall time over the compare scenes, s (log)'\n"
           "set ylabel 'largest |energy drift| of an elastic scene (log; exact at 1e-40)'\n"
           "set title 'PGE against Box2D and Chipmunk: speed against energy error'\nplot " + plot +
           "\nunset title\n" + LogFrame::kUnfixed;
      p.files.push_back("peers.svg");
    }
  }
  // Energy drift along a long run, and events per second against body count.
  for (const RowKind kind : {RowKind::Drift, RowKind::Scaling}) {
    std::string plot, data;
    int block = 0;
    std::map<std::string, std::vector<const Row*>> series;  // per configuration
    for (const Row& x : r.rows)
      if (x.kind == kind && x.error.empty()) series[fmt::format("{:02d}{}", config_order(x.solver, x.scalar), x.config())].push_back(&x);
    for (auto& [key, rows] : series) {
      const Row& first = *rows.front();
      if (kind == RowKind::Drift) {
        // The largest drift so far: the signed drift crosses zero often, which a log axis cannot show.
        double worst = 0;
        for (const auto& [events, drift] : first.series) {
          worst = std::max(worst, std::abs(drift));
          data += fmt::format("{} {}\n", g(events), g(on_log(worst)));
        }
      } else {
        std::sort(rows.begin(), rows.end(), [](const Row* a, const Row* b) { return a->bodies < b->bodies; });
        for (const Row* x : rows) data += fmt::format("{} {}\n", x->bodies, g(x->events_per_second));
      }
      data += "\n\n";
      plot += fmt::format("{}'{}' index {} using 1:2 with linespoints pt 7 ps 0.6 {} title '{}'", plot.empty() ? "" : ", \\\n  ",
                          kind == RowKind::Drift ? "drift.dat" : "scaling.dat", block++, style_of(first.solver, first.scalar),
                          first.config());
    }
    if (plot.empty()) continue;
    if (kind == RowKind::Drift) {
      write_file(dir / "drift.dat", data);
      const Row& any = *series.begin()->second.front();
      s += kTerminal;
      s += "set output 'drift.svg'\nset logscale y\nset format y '10^{%L}'\n"
           "set xlabel 'contact events'\nset ylabel 'largest |E - E_0| / E_0 so far (log; exact at 1e-40)'\n"
           "set title " + gp_quoted(fmt::format("Energy drift along a long run: {} ({} bodies)", any.scene, any.bodies)) +
           "\nplot " + plot + "\nunset title\nunset logscale\nunset format\n";
      p.files.push_back("drift.svg");
    } else {
      write_file(dir / "scaling.dat", data);
      s += kTerminal;
      s += "set output 'scaling.svg'\nset logscale xy\n"
           "set xlabel 'moving bodies (elastic gas, area fraction 0.3; log)'\nset ylabel 'events per second (log)'\n"
           "set title 'Events per second against body count'\nplot " + plot + "\nunset title\nunset logscale\n";
      p.files.push_back("scaling.svg");
    }
  }
  return p;
}

void run_gnuplot(const fs::path& dir, const Plots& plots, const std::string& gnuplot) {
  write_file(dir / "plots.gp", plots.script);
  for (const std::string& f : plots.files) fs::remove(dir / f);
  const std::string log = (dir / "gnuplot.log").string();
  const std::string command =
      fmt::format("cd '{}' && '{}' plots.gp > gnuplot.log 2>&1", dir.string(), gnuplot);
  const int status = std::system(command.c_str());
  if (status != 0) {
    const std::string said = fs::exists(log) ? read_text_file(log) : std::string();
    throw ReportError(fmt::format("gnuplot failed (exit status {}); is it installed (Debian: gnuplot-nox)? {}{}", status,
                                  log, said.empty() ? "" : ":\n" + said.substr(0, 2000)));
  }
  for (const std::string& f : plots.files)
    if (!fs::exists(dir / f) || fs::file_size(dir / f) == 0) throw ReportError("gnuplot did not write " + (dir / f).string());
}

std::string sci(double x) { return x == 0 ? "0" : fmt::format("{:.2e}", x); }

// The configuration table, one line per solver x scalar (Markdown; the HTML page converts it).
std::vector<std::vector<std::string>> config_table(const std::vector<ConfigSummary>& configs) {
  std::vector<std::vector<std::string>> t;
  t.push_back({"solver", "scalar", "scenes", "events", "judged", "misses", "phantoms", "misorders", "p99 rel. error",
               "max rel. error", "max ulps", "worst energy drift", "events/s", "ns/prediction", "Pareto"});
  for (const ConfigSummary& c : configs) {
    t.push_back({c.solver, c.scalar, fmt::format("{}{}", c.scenes, c.failed_runs ? fmt::format(" ({} failed)", c.failed_runs) : ""),
                 std::to_string(c.events), std::to_string(c.judged_events), std::to_string(c.misses),
                 std::to_string(c.phantoms), std::to_string(c.misorders), sci(c.rel_p99), sci(c.rel_max), g(c.ulps_max),
                 sci(c.worst_energy_drift), fmt::format("{:.0f}", c.events_per_second), fmt::format("{:.0f}", c.ns_per_prediction),
                 c.pareto ? "yes" : ""});
  }
  return t;
}

// Per scene: the largest |ulps| of each configuration, "miss"/"phantom" when there were any.
std::vector<std::vector<std::string>> scene_table(const Results& r, const std::vector<ConfigSummary>& configs) {
  std::vector<std::vector<std::string>> t;
  std::vector<std::string> head{"family", "scene", "bodies"};
  std::map<std::string, std::size_t> column;
  for (const ConfigSummary& c : configs) {
    column[c.solver + "/" + c.scalar] = head.size();
    head.push_back(c.solver + "/" + c.scalar);
  }
  t.push_back(head);
  std::map<std::string, std::size_t> line;
  for (const Row& x : r.rows) {
    if (x.kind != RowKind::Accuracy) continue;
    const std::string key = x.family + "/" + x.scene;
    if (!line.count(key)) {
      line[key] = t.size();
      std::vector<std::string> row(head.size());
      row[0] = x.family;
      row[1] = x.scene;
      row[2] = std::to_string(x.bodies);
      t.push_back(row);
    }
    std::string cell = !x.error.empty() ? "error" : x.judged_events == 0 ? "-" : g(x.ulps_max);
    if (x.misses) cell += fmt::format(" {} miss", x.misses);
    if (x.phantoms) cell += fmt::format(" {} phantom", x.phantoms);
    t[line[key]][column[x.config()]] = cell;
  }
  return t;
}

// One line per compare scene x setting.
std::vector<std::vector<std::string>> peer_table(const Results& r) {
  std::vector<std::vector<std::string>> t;
  t.push_back({"scene", "engine", "setting", "wall s", "energy drift", "momentum drift", "penetration", "tunnelled",
               "final-state error"});
  for (const Row& x : r.rows) {
    if (x.kind != RowKind::Peer) continue;
    if (!x.error.empty()) {
      t.push_back({x.scene, x.solver, x.scalar, "error: " + x.error, "", "", "", "", ""});
      continue;
    }
    t.push_back({x.scene, x.solver, x.scalar, g(x.wall_seconds), sci(x.energy_drift), sci(x.momentum_drift),
                 sci(x.overlap), std::to_string(x.tunnelled), sci(x.final_error)});
  }
  return t;
}

std::string markdown_table(const std::vector<std::vector<std::string>>& t) {
  std::string out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    out += "|";
    for (const std::string& c : t[i]) out += " " + c + " |";
    out += "\n";
    if (i == 0) {
      out += "|";
      for (std::size_t k = 0; k < t[i].size(); ++k) out += " --- |";
      out += "\n";
    }
  }
  return out;
}

std::string html_table(const std::vector<std::vector<std::string>>& t) {
  std::string out = "<table>\n";
  for (std::size_t i = 0; i < t.size(); ++i) {
    out += "<tr>";
    for (const std::string& c : t[i]) out += (i == 0 ? "<th>" : "<td>") + html_escaped(c) + (i == 0 ? "</th>" : "</td>");
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

struct Section {
  std::string title, text, plot;  // plot: a file in plots/ (empty: none)
};

std::string meta_text(const Meta& m, const std::string& command) {
  std::string shards = m.shards == 1 ? "not sharded"
                                     : fmt::format("{} of {} shards merged", m.shards_merged.empty() ? 1 : m.shards_merged.size(), m.shards);
  return fmt::format(
      "Commit {}{}; made {}; {} report, random scenes from seed {}; {}.\n"
      "Machine: {}, {} cores, {}. Build: {} {}{}{}. Calibration workload: {:.4f} s.\n"
      "Command: `{}`{}",
      m.commit, m.dirty ? " (with uncommitted changes)" : "", m.created, m.quick ? "quick" : "full", m.seed, shards, m.cpu,
      m.cores, m.os, m.compiler, m.build_type, m.validate ? ", expensive validation on (slower)" : "",
      m.sanitize ? ", sanitizers on (much slower)" : "", m.calibration_seconds, command,
      m.injected.empty() ? "" : fmt::format("\n\n**This report was made with a deliberate regression: {}.**", m.injected));
}

}  // namespace

std::vector<std::string> plot_files() {
  return {"speed_error.svg", "error_cdf.svg", "drift.svg", "scaling.svg", "peers.svg"};
}

void write_page(const Results& r, const std::string& dir_name, const PageInputs& in) {
  const fs::path dir(dir_name);
  const fs::path plots_dir = dir / "plots";
  std::error_code ec;
  fs::create_directories(plots_dir, ec);
  if (ec) throw ReportError("cannot create " + plots_dir.string() + ": " + ec.message());
  const std::vector<ConfigSummary> configs = summarize(r);
  const Plots plots = make_plots(r, configs, plots_dir);
  run_gnuplot(plots_dir, plots, in.gnuplot);
  const auto has = [&plots](const std::string& f) {
    return std::find(plots.files.begin(), plots.files.end(), f) != plots.files.end();
  };

  std::vector<Section> sections;
  sections.push_back({"Speed against error",
                      "Each point is one solver x scalar over every fixture and random scene: the time per contact event "
                      "of the engine alone (no oracle; the median of repeated runs), against the 99th percentile of the "
                      "relative time error of its events, judged by the exact oracle (CGAL root isolation). Points on the "
                      "Pareto front are joined: no other configuration is both faster and more accurate (accuracy "
                      "ranks misses and phantoms first, then the p99 error). Black crosses "
                      "mark configurations with misses or phantoms (a collision the engine skipped, or one that never "
                      "happens).",
                      has("speed_error.svg") ? "speed_error.svg" : ""});
  sections.push_back({"Error CDFs",
                      "The distribution of every judged event's relative time error, per configuration. Errors are binned "
                      "by binary exponent, and a bin is drawn at its upper bound, so the curves never flatter an engine.",
                      has("error_cdf.svg") ? "error_cdf.svg" : ""});
  sections.push_back({"Energy drift over a long run",
                      "The largest relative change of total energy so far, along one long elastic-gas run per "
                      "configuration (the engine alone). Every collision is elastic, so the exact answer is no drift at "
                      "all: what shows is rounding in impulses and positions.",
                      has("drift.svg") ? "drift.svg" : ""});
  sections.push_back({"Events per second against body count",
                      "The elastic gas (area fraction 0.3, no gravity) at several sizes, timed without the oracle: the "
                      "broad phase keeps the cost of an event nearly flat.",
                      has("scaling.svg") ? "scaling.svg" : ""});

  sections.push_back({"Against Box2D and Chipmunk",
                      "The pge compare scenes (fixtures/scenes/peers: a 1,000-ball gas for 10 s, the same under "
                      "gravity, a 5-ball Newton's cradle, a head-on collision, a bullet against a thin wall, a snooker "
                      "break), run by PGE in every solver x scalar and by Box2D 2.4 and Chipmunk 7 at 60, 240 and "
                      "1000 Hz with their default and high iteration counts (friction and damping 0, no sleeping, "
                      "restitution threshold 0, Box2D bullets; peers/include/pge/peers.hpp says why each setting). One "
                      "point per setting: its wall time over the scenes against the largest energy drift of an elastic "
                      "scene (the exact answer is 0; drifts summed in long double, or quad for quad); PGE's point "
                      "shape is its solver, and its scalars sit at their precisions (robust's points are named); "
                      "crosses mark settings where a body tunnelled through a fixed body. The table below has every "
                      "measure, against PGE certified double as the reference.",
                      has("peers.svg") ? "peers.svg" : ""});
  const auto config_rows = config_table(configs);
  const auto scene_rows = scene_table(r, configs);

  // report.md
  std::string md = "# PGE accuracy report\n\n" + meta_text(r.meta, in.command) + "\n\n";
  md += "## Configurations\n\nOne line per solver x scalar over the fixture and random scenes (misses and phantoms per "
        "the exact oracle; time errors relative to the exact contact time; events/s of the engine alone).\n\n";
  md += markdown_table(config_rows) + "\n";
  for (const Section& sec : sections) {
    md += "## " + sec.title + "\n\n" + sec.text + "\n\n";
    md += sec.plot.empty() ? "Not measured in this report.\n\n" : "![" + sec.title + "](plots/" + sec.plot + ")\n\n";
  }
  const auto peer_rows = peer_table(r);
  if (peer_rows.size() > 1)
    md += "## Peers, every measure\n\nPenetration as a fraction of the smaller body's size; final-state error: RMS "
          "position error at the horizon against PGE certified, over the scene's extent.\n\n" +
          markdown_table(peer_rows) + "\n";
  md += "## Scenes\n\nThe largest |time error| of each scene, in ulps of the engine's scalar (\"-\": no event had an exact "
        "time to compare; misses and phantoms named).\n\n";
  md += markdown_table(scene_rows) + "\n";
  md += "## Data\n\n`results.json` (pge-report/1: every row, with histograms and series; what `pge gate` reads) and "
        "`results.csv` (one row per scene x configuration).\n";
  write_file(dir / "report.md", md);

  // index.html: everything inline, so that it opens offline and from anywhere.
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>PGE accuracy report</title>\n"
      "<link rel=\"icon\" href=\"data:,\">\n<style>\n"
      "body{font-family:Helvetica,Arial,sans-serif;margin:2em auto;max-width:1100px;color:#222;line-height:1.45}\n"
      "table{border-collapse:collapse;font-size:12px;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}\n"
      "th{background:#f4f4f4}td:first-child,td:nth-child(2){text-align:left}img{max-width:100%;border:1px solid #eee}\n"
      ".pictures{display:flex;flex-wrap:wrap;gap:1em}.pictures figure{margin:0;width:340px}\n"
      ".pictures img{width:340px;height:260px;object-fit:contain;background:#fff}code{background:#f4f4f4;padding:0 3px}\n"
      ".scroll{overflow-x:auto}\n</style>\n</head>\n<body>\n<h1>PGE accuracy report</h1>\n";
  std::string meta = html_escaped(meta_text(r.meta, in.command));
  for (std::size_t at = meta.find('\n'); at != std::string::npos; at = meta.find('\n', at + 4)) meta.replace(at, 1, "<br>");
  html += "<p>" + meta + "</p>\n<h2>Configurations</h2>\n<div class=\"scroll\">" + html_table(config_rows) + "</div>\n";
  for (const Section& sec : sections) {
    html += "<h2>" + html_escaped(sec.title) + "</h2>\n<p>" + html_escaped(sec.text) + "</p>\n";
    if (sec.plot.empty()) {
      html += "<p>Not measured in this report.</p>\n";
    } else {
      html += fmt::format("<img alt=\"{}\" src=\"data:image/svg+xml;base64,{}\">\n", html_escaped(sec.title),
                          base64(read_text_file((plots_dir / sec.plot).string())));
    }
  }
  if (!in.pictures.empty()) {
    html += "<h2>Fixture families</h2>\n<p>One scene of each family, simulated with the robust solver in double "
            "(pge render): trajectories, collision points in red.</p>\n<div class=\"pictures\">\n";
    for (const auto& [family, svg] : in.pictures)
      html += fmt::format("<figure><img alt=\"{0}\" src=\"data:image/svg+xml;base64,{1}\"><figcaption>{0}</figcaption></figure>\n",
                          html_escaped(family), base64(svg));
    html += "</div>\n";
  }
  if (peer_rows.size() > 1)
    html += "<h2>Peers, every measure</h2>\n<div class=\"scroll\">" + html_table(peer_rows) + "</div>\n";
  html += "<h2>Scenes</h2>\n<p>The largest |time error| of each scene, in ulps of the engine's scalar.</p>\n<div "
          "class=\"scroll\">" + html_table(scene_rows) + "</div>\n";
  html += "<h2>Data</h2>\n<p><code>results.json</code> and <code>results.csv</code> beside this page.</p>\n</body>\n</html>\n";
  write_file(dir / "index.html", html);
  // The pictures as files too, for report.md's readers.
  for (const auto& [family, svg] : in.pictures) write_file(plots_dir / ("family-" + family + ".svg"), svg);
}

}  // namespace pge::report
