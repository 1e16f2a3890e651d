#include "scatterlab/validate/half_space_comparison.hpp"

#include <cmath>
#include <limits>

#include "scatterlab/core/error.hpp"
#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/grosjean_half_space.hpp"

namespace scatterlab {
namespace {

// Mean relative error against the Monte Carlo over resolved bins; `near` tells a bin's range.
template <typename IsNear>
void score(ModelCurve& curve, const std::optional<MonteCarloCurve>& mc, IsNear is_near) {
  if (!mc) {
    curve.near_error = curve.far_error = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  double near = 0.0, far = 0.0;
  int n_near = 0, n_far = 0;
  for (std::size_t i = 0; i < curve.values.size(); ++i) {
    if (!(mc->mean[i] > 3.0 * mc->stderr_of_mean[i]) || !(mc->mean[i] > 0.0)) continue;
    const double e = std::abs(curve.values[i] - mc->mean[i]) / mc->mean[i];
    if (is_near(i)) {
      near += e, ++n_near;
    } else {
      far += e, ++n_far;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  curve.near_error = n_near ? near / n_near : nan;
  curve.far_error = n_far ? far / n_far : nan;
}

void check_mc(const std::optional<MonteCarloCurve>& mc, std::size_t bins, const std::string& what) {
  if (mc && (mc->mean.size() != bins || mc->stderr_of_mean.size() != bins)) {
    throw InputError("monte_carlo", what + " has " + std::to_string(mc->mean.size()) + " bins",
                     std::to_string(bins) + " bins (mean and stderr), as the model grid");
  }
}

}  // namespace

HalfSpaceComparison compare_half_space(const HalfSpaceMedium& medium, double entry_transmittance,
                                       std::span<const double> r_edges,
                                       std::span<const double> z_edges,
                                       std::optional<MonteCarloCurve> reflectance_mc,
                                       std::optional<MonteCarloCurve> fluence_mc,
                                       double near_limit) {
  medium.validate();
  if (!(entry_transmittance >= 0.0 && entry_transmittance <= 1.0)) {
    throw InputError("entry_transmittance", "got " + std::to_string(entry_transmittance), "[0, 1]");
  }
  HalfSpaceComparison c;
  c.medium = medium;
  c.entry_transmittance = entry_transmittance;
  c.near_limit = near_limit;
  c.r_edges.assign(r_edges.begin(), r_edges.end());
  c.z_edges.assign(z_edges.begin(), z_edges.end());
  const std::size_t nr = r_edges.size() > 0 ? r_edges.size() - 1 : 0;
  const std::size_t nz = z_edges.size() > 0 ? z_edges.size() - 1 : 0;
  check_mc(reflectance_mc, nr, "reflectance");
  check_mc(fluence_mc, nr * nz, "fluence");
  c.reflectance_mc = std::move(reflectance_mc);
  c.fluence_mc = std::move(fluence_mc);

  const auto scale = [entry_transmittance](std::vector<double> v) {
    for (double& x : v) x *= entry_transmittance;
    return v;
  };
  const DipoleModel dipole = classical_dipole(medium);
  const DipoleModel better = better_dipole(medium);
  const GrosjeanHalfSpace grosjean = grosjean_half_space(medium);
  c.reflectance = {
      {"dipole", scale(dipole_reflectance_annulus_average(dipole, r_edges)),
       entry_transmittance * dipole_total_reflectance(dipole)},
      {"better_dipole", scale(dipole_reflectance_annulus_average(better, r_edges)),
       entry_transmittance * dipole_total_reflectance(better)},
      {"grosjean", scale(grosjean_half_space_reflectance_annulus_average(grosjean, r_edges)),
       entry_transmittance * grosjean_half_space_total_reflectance(grosjean)},
  };
  for (ModelCurve& curve : c.reflectance) {
    score(curve, c.reflectance_mc, [&](std::size_t i) { return r_edges[i + 1] <= near_limit; });
  }
  if (nz > 0) {
    c.fluence = {
        {"dipole", scale(dipole_fluence_cell_average(dipole, r_edges, z_edges))},
        {"better_dipole", scale(dipole_fluence_cell_average(better, r_edges, z_edges))},
        {"grosjean", scale(grosjean_half_space_fluence_cell_average(grosjean, r_edges, z_edges))},
    };
    // Near: cells whose far corner is within near_limit of the entry point.
    for (ModelCurve& curve : c.fluence) {
      score(curve, c.fluence_mc, [&](std::size_t k) {
        const double r1 = r_edges[k / nz + 1], z1 = z_edges[k % nz + 1];
        return std::hypot(r1, z1) <= near_limit;
      });
    }
  }
  return c;
}

}  // namespace scatterlab
