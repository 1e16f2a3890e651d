#pragma once
// Minimal interval arithmetic for the Krawczyk test of Walter et al. 2009, §3.3.2 (Moore 1977).
// Results are widened by a few ulps per operation instead of switching the rounding mode, which
// keeps the enclosures outward-rounded for the magnitudes the solver meets (|x| <~ 1e6).

#include <algorithm>
#include <cmath>
#include <limits>

#include "scatterlab/core/frame.hpp"

namespace scatterlab {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;

  Interval() = default;
  constexpr Interval(double value) : lo(value), hi(value) {}  // NOLINT: points are intervals
  constexpr Interval(double low, double high) : lo(low), hi(high) {}

  double mid() const { return 0.5 * (lo + hi); }
  double width() const { return hi - lo; }
  double magnitude() const { return std::max(std::abs(lo), std::abs(hi)); }
  bool contains(double x) const { return lo <= x && x <= hi; }
};

inline Interval widen(Interval x) {
  constexpr double ulps = 4.0 * std::numeric_limits<double>::epsilon();
  const double slack = ulps * std::max(std::abs(x.lo), std::abs(x.hi)) + 1e-300;
  return {x.lo - slack, x.hi + slack};
}

inline Interval operator+(Interval a, Interval b) { return widen({a.lo + b.lo, a.hi + b.hi}); }
inline Interval operator-(Interval a, Interval b) { return widen({a.lo - b.hi, a.hi - b.lo}); }
inline Interval operator-(Interval a) { return {-a.hi, -a.lo}; }
inline Interval operator*(Interval a, Interval b) {
  const double p1 = a.lo * b.lo, p2 = a.lo * b.hi, p3 = a.hi * b.lo, p4 = a.hi * b.hi;
  return widen({std::min({p1, p2, p3, p4}), std::max({p1, p2, p3, p4})});
}
inline Interval square(Interval a) {
  const double l = a.lo * a.lo, h = a.hi * a.hi;
  if (a.lo >= 0.0) return widen({l, h});
  if (a.hi <= 0.0) return widen({h, l});
  return widen({0.0, std::max(l, h)});
}
inline Interval sqrt(Interval a) {
  return widen({std::sqrt(std::max(0.0, a.lo)), std::sqrt(std::max(0.0, a.hi))});
}
// 1 / a for a strictly positive interval (callers check a.lo > 0).
inline Interval reciprocal(Interval a) { return widen({1.0 / a.hi, 1.0 / a.lo}); }
inline Interval intersect(Interval a, Interval b) {
  return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)};
}

struct IntervalVec3 {
  Interval x, y, z;

  IntervalVec3() = default;
  IntervalVec3(Interval a, Interval b, Interval c) : x(a), y(b), z(c) {}
  IntervalVec3(const Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}  // NOLINT

  Interval operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }
};

inline IntervalVec3 operator+(const IntervalVec3& a, const IntervalVec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline IntervalVec3 operator-(const IntervalVec3& a, const IntervalVec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline IntervalVec3 operator*(Interval s, const IntervalVec3& v) {
  return {s * v.x, s * v.y, s * v.z};
}
inline Interval dot(const IntervalVec3& a, const IntervalVec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Interval squared_norm(const IntervalVec3& a) {
  return square(a.x) + square(a.y) + square(a.z);
}

}  // namespace scatterlab
