#pragma once
// One section of the accuracy report: what was run, the exact reference it was compared with,
// the tolerance, a table of results (written as Markdown and as CSV) and the checks that
// decide whether the section passed.

#include <string>
#include <vector>

#include "scatterlab/io/plot.hpp"

namespace scatterlab::report {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  // each row has columns.size() cells
};

// A pass/fail criterion with the numbers that decided it.
struct Check {
  std::string what;  // e.g. "albedo 0.5, g 0.9: mean absorption depth within 5 sigma"
  bool passed = false;
};

// A figure of the report, written as <id>.png beside report.md.
struct Figure {
  std::string id;
  LinePlot plot;
};

struct Section {
  std::string id;          // file stem of its CSV, e.g. "infinite_medium_convergence"
  std::string title;
  std::string reference;   // the exact solution or identity it is compared with
  std::string tolerance;   // the tolerance, and why it is the right one
  std::string findings;    // Markdown: what the numbers show
  Table table;
  std::vector<Figure> figures;
  std::vector<Check> checks;
  int non_finite_values = 0;  // NaN or Inf seen anywhere in the section's results; must be 0

  bool passed() const;
  std::size_t checks_passed() const;
  std::vector<std::string> failures() const;  // the checks that failed, plus any NaN/Inf count
};

}  // namespace scatterlab::report
