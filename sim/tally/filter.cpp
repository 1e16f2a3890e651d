#include "scatterlab/tally/filter.hpp"

#include <cmath>
#include <stdexcept>

#include "scatterlab/core/constants.hpp"

namespace scatterlab {
namespace {

std::size_t count(const UniformAxis& axis) {
  return static_cast<std::size_t>(axis.bins);
}

template <class Measure>
std::vector<double> per_bin(const UniformAxis& axis, Measure&& measure) {
  std::vector<double> m(count(axis));
  for (int i = 0; i < axis.bins; ++i)
    m[static_cast<std::size_t>(i)] = measure(axis.edge(i), axis.edge(i + 1));
  return m;
}

// A coordinate by its bin width.
Filter length_filter(const std::string& name, const UniformAxis& axis, Coordinate coordinate) {
  return {{name},
          {count(axis)},
          std::vector<double>(count(axis), axis.width()),
          {coordinate, AxisLookup(axis), 0.0}};
}

}  // namespace

Filter radius_filter(const UniformAxis& r) {
  return {{"r"},
          {count(r)},
          per_bin(r, [](double r0, double r1) { return pi * (r1 * r1 - r0 * r0); }),
          {Coordinate::r, AxisLookup(r), 0.0}};
}

Filter position_filter(Coordinate coordinate, const UniformAxis& axis) {
  if (coordinate != Coordinate::x && coordinate != Coordinate::y && coordinate != Coordinate::z) {
    throw std::invalid_argument("position_filter: x, y or z");
  }
  const char* name = coordinate == Coordinate::x ? "x" : coordinate == Coordinate::y ? "y" : "z";
  return length_filter(name, axis, coordinate);
}

Filter depth_filter(const UniformAxis& z) {
  return position_filter(Coordinate::z, z);
}

Filter time_filter(const UniformAxis& t, double seconds_per_path) {
  Filter f = length_filter("t", t, Coordinate::t);
  f.binning.seconds_per_path = seconds_per_path;
  return f;
}

Filter direction_filter(const UniformAxis& theta, const UniformAxis& phi, bool fold_phi) {
  Filter f{{"theta", "phi"}, {count(theta), count(phi)}, {}, {Coordinate::direction, {}, 0.0}};
  f.measures.reserve(count(theta) * count(phi));
  for (int k = 0; k < theta.bins; ++k) {
    const double band = std::cos(theta.edge(k)) - std::cos(theta.edge(k + 1));
    const double solid_angle = band * phi.width() * (fold_phi ? 2.0 : 1.0);
    f.measures.insert(f.measures.end(), count(phi), solid_angle);
  }
  return f;
}

Filter shell_filter(const UniformAxis& rho) {
  return {{"rho"},
          {count(rho)},
          per_bin(rho, [](double a, double b) { return 4.0 / 3.0 * pi * (b * b * b - a * a * a); }),
          {Coordinate::rho, AxisLookup(rho), 0.0}};
}

Filter exit_angle_filter(const UniformAxis& theta_o) {
  return {{"theta_o"},
          {count(theta_o)},
          per_bin(theta_o,
                  [](double t0, double t1) {
                    const double s0 = std::sin(t0), s1 = std::sin(t1);
                    return pi * (s1 * s1 - s0 * s0);
                  }),
          {Coordinate::exit_angle, AxisLookup(theta_o), 0.0}};
}

Filter exit_solid_angle_filter(const UniformAxis& theta_o, bool with_azimuth) {
  const double turn = with_azimuth ? 1.0 : 2.0 * pi;
  return {{"theta_o"},
          {count(theta_o)},
          per_bin(theta_o,
                  [turn](double t0, double t1) { return turn * (std::cos(t0) - std::cos(t1)); }),
          {Coordinate::exit_angle, AxisLookup(theta_o), 0.0}};
}

Filter polar_angle_filter(const UniformAxis& theta, bool with_azimuth) {
  Filter f = exit_solid_angle_filter(theta, with_azimuth);
  f.dims = {"theta"};
  f.binning.coordinate = Coordinate::theta;
  return f;
}

Filter azimuth_angle_filter(const UniformAxis& phi) {
  return length_filter("phi", phi, Coordinate::phi);
}

Filter sphere_polar_filter(const UniformAxis& psi, double radius, bool with_azimuth) {
  const double band = (with_azimuth ? 1.0 : 2.0 * pi) * radius * radius;
  return {
      {"psi"},
      {count(psi)},
      per_bin(psi, [band](double p0, double p1) { return band * (std::cos(p0) - std::cos(p1)); }),
      {Coordinate::psi, AxisLookup(psi), 0.0}};
}

Filter sphere_azimuth_filter(const UniformAxis& azimuth, double radius, bool with_psi) {
  Filter f = length_filter("azimuth", azimuth, Coordinate::azimuth);
  if (!with_psi) {
    for (double& m : f.measures) m *= 2.0 * radius * radius;
  }
  return f;
}

Filter order_filter(int bins) {
  const UniformAxis orders{0.0, static_cast<double>(bins), bins};
  return length_filter("order", orders, Coordinate::order);
}

Filter layer_filter(std::size_t layers) {
  const auto count = static_cast<double>(layers);
  return {{"layer"},
          {layers},
          std::vector<double>(layers, 1.0),
          {Coordinate::layer, AxisLookup(UniformAxis{0.0, count, static_cast<int>(layers)}), 0.0}};
}

Filter sphere_patch_filter(const UniformAxis& psi, const UniformAxis& azimuth, double radius) {
  Filter f{
      {"psi", "azimuth"}, {count(psi), count(azimuth)}, {}, {Coordinate::surface_patch, {}, 0.0}};
  for (int k = 0; k < psi.bins; ++k) {
    const double band = std::cos(psi.edge(k)) - std::cos(psi.edge(k + 1));
    f.measures.insert(f.measures.end(), count(azimuth), radius * radius * band * azimuth.width());
  }
  return f;
}

Filter triangle_filter(const std::vector<double>& areas) {
  const auto count = static_cast<int>(areas.size());
  return {
      {"triangle"},
      {areas.size()},
      areas,
      {Coordinate::triangle, AxisLookup(UniformAxis{0.0, static_cast<double>(count), count}), 0.0}};
}

Filter component_filter(std::size_t components) {
  return {{"component"},
          {components},
          std::vector<double>(components, 1.0),
          {Coordinate::component, {}, 0.0}};
}

Filter grid_region_filter(bool inside) {
  return {{}, {}, {1.0}, {inside ? Coordinate::inside_grid : Coordinate::outside_grid, {}, 0.0}};
}

}  // namespace scatterlab
