// The accuracy report's pages: report.md and a self-contained index.html (plots inline as data
// URIs, no network, no script), with the plots drawn by gnuplot from data files kept beside them.
#pragma once

#include "pge/report_data.hpp"

#include <string>
#include <utility>
#include <vector>

namespace pge::report {

struct PageInputs {
  std::string command;  // the command line that made the results (shown on the page)
  std::vector<std::pair<std::string, std::string>> pictures;  // (family, SVG document) per fixture family
  std::string gnuplot = "gnuplot";                            // the plotting program
};

// Writes DIR/report.md, DIR/index.html and DIR/plots/ (*.dat, plots.gp, *.svg). Throws
// ReportError when gnuplot is missing or fails, or a file cannot be written; the data files
// (results.json, results.csv) are the caller's and written before.
void write_page(const Results& r, const std::string& dir, const PageInputs& in);

// The plots the page shows, by file name in DIR/plots/ (for tests and the README).
std::vector<std::string> plot_files();

}  // namespace pge::report
