#pragma once
// A uniform binning of one coordinate: `bins` equal cells between `min` and `max`.

#include <cmath>
#include <string>
#include <vector>

namespace scatterlab {

struct UniformAxis {
  double min = 0.0;
  double max = 1.0;
  int bins = 1;

  double width() const { return (max - min) / bins; }
  double inverse_width() const { return bins / (max - min); }

  // The cell holding x, or -1 outside [min, max) (AxisLookup::index).
  int index(double x) const;

  double edge(int i) const { return i == bins ? max : min + i * width(); }
  double center(int i) const { return min + (i + 0.5) * width(); }

  std::vector<double> edges() const {
    std::vector<double> e(static_cast<std::size_t>(bins) + 1);
    for (int i = 0; i <= bins; ++i) e[static_cast<std::size_t>(i)] = edge(i);
    return e;
  }

  bool operator==(const UniformAxis&) const = default;
};

// A UniformAxis's cell lookup with the inverse width computed once, for the walk's scorer:
// UniformAxis::index divides on every call, and there the compiler cannot hoist the division
// out of the loop, since a store into the tally buffer (a double*) may alias the axis. The
// arithmetic is the same, so the cells are the same to the bit.
struct AxisLookup {
  double min = 0.0;
  double inverse_width = 1.0;
  double end = 1.0;  // bins, as the upper bound of (x - min) * inverse_width

  AxisLookup() = default;
  explicit AxisLookup(const UniformAxis& axis)
      : min(axis.min), inverse_width(axis.inverse_width()), end(axis.bins) {}

  // The cell holding x, or -1 outside [min, max). Branch-light: one compare for the range.
  int index(double x) const {
    const double u = (x - min) * inverse_width;
    return (u >= 0.0 && u < end) ? static_cast<int>(u) : -1;
  }
};

inline int UniformAxis::index(double x) const {
  return AxisLookup(*this).index(x);
}

}  // namespace scatterlab
