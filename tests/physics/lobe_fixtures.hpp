#pragma once
// Synthetic lobes for the fit tests: a model's bin averages on an angular grid, optionally with
// Gaussian noise of a given relative size drawn from Philox (fixed seeds).

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "scatterlab/core/random.hpp"
#include "scatterlab/fit/lobe_fit.hpp"

namespace scatterlab::testing {

struct SyntheticLobe {
  std::vector<double> mean, stderr_of_mean;
  Eigen::Vector3d flux = Eigen::Vector3d::Zero();

  fit::LobeData data() const { return {mean, stderr_of_mean, flux}; }
};

// A standard normal deviate from two uniforms (Box-Muller).
inline double normal_deviate(PhotonRandom& random) {
  const auto u = random.next4();
  return std::sqrt(-2.0 * std::log(u[0])) * std::cos(2.0 * std::numbers::pi * u[1]);
}

// Bin averages of `model` with `truth` on `grid` (use a higher quadrature order than the fit's,
// so that the fit does not see its own quadrature), times (1 + relative_noise * N(0, 1)), with
// stderr = relative_noise * the true average (what a tally with that noise would report).
inline SyntheticLobe synthesize(fit::LobeModel model, const fit::LobeParameters& truth,
                                const fit::LobeGrid& grid, double relative_noise = 0.0,
                                std::uint64_t seed = 1) {
  SyntheticLobe lobe;
  for (std::size_t bin = 0; bin < grid.size(); ++bin) {
    const double value = std::exp(fit::log_bin_average(model, grid, bin, truth));
    PhotonRandom random(seed, bin);
    const double noise = relative_noise > 0.0 ? relative_noise * normal_deviate(random) : 0.0;
    lobe.mean.push_back(value * (1.0 + noise));
    lobe.stderr_of_mean.push_back(relative_noise * value);
    lobe.flux += grid.solid_angle(bin) * lobe.mean.back() * grid.centre(bin);
  }
  return lobe;
}

inline Eigen::Vector3d direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

inline fit::LobeParameters parameters(const Eigen::Vector3d& axis, std::array<double, 4> shape) {
  fit::LobeParameters p;
  p.axis = axis.normalized();
  p.shape = shape;
  return p;
}

inline std::vector<double> uniform_edges(double max, std::size_t bins) {
  std::vector<double> edges;
  for (std::size_t i = 0; i <= bins; ++i)
    edges.push_back(max * static_cast<double>(i) / static_cast<double>(bins));
  return edges;
}

// The paper's angular grid (18 x 36, unfolded) or a finer one.
inline fit::LobeGrid angular_grid(std::size_t theta_bins, std::size_t phi_bins, int order,
                                  bool folded = false) {
  return fit::LobeGrid(uniform_edges(std::numbers::pi, theta_bins),
                       uniform_edges((folded ? 1.0 : 2.0) * std::numbers::pi, phi_bins), folded,
                       order);
}

}  // namespace scatterlab::testing
