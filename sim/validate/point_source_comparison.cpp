#include "scatterlab/validate/point_source_comparison.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "point_source_models.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace scatterlab {
namespace {

// Over the shells where `use` is true (all when empty).
RangeError relative_error(const std::vector<double>& model, const std::vector<double>& exact,
                          const std::vector<double>& rho_hi, double near_limit,
                          const std::vector<bool>& use = {}) {
  double near = 0.0, far = 0.0;
  int n_near = 0, n_far = 0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (!(exact[i] > 0.0) || (!use.empty() && !use[i])) continue;
    const double e = std::abs(model[i] - exact[i]) / exact[i];
    if (rho_hi[i] <= near_limit) {
      near += e, ++n_near;
    } else {
      far += e, ++n_far;
    }
  }
  return {n_near ? near / n_near : 0.0, n_far ? far / n_far : 0.0};
}

}  // namespace

PointSourceComparison compare_point_source(double albedo,
                                           const PointSourceComparisonSettings& settings) {
  InfiniteMediumSpec spec;
  spec.set_source(SourceKind::point);
  spec.medium.albedo = albedo;
  spec.medium.g = 0.0;
  spec.tallies = TallyRequest{false, false, false, true, false, Estimator::collision};
  spec.grid.rho = settings.rho;
  spec.run.photons = settings.photons;
  spec.run.batches = settings.batches;
  spec.run.seed = settings.seed;
  spec.run.threads = settings.threads;
  spec.validate();
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult* fluence = find_tally(out.tallies, "fluence_spherical");
  if (fluence == nullptr)
    throw std::logic_error("compare_point_source: no fluence_spherical tally");

  PointSourceComparison c;
  c.albedo = albedo;
  c.wall_seconds = out.wall_seconds;
  const UniformAxis& axis = settings.rho;
  PointSourceCurves curves = point_source_shell_averages(albedo, axis.edges());
  c.exact = std::move(curves.exact);
  c.diffusion = std::move(curves.diffusion);
  c.grosjean = std::move(curves.grosjean);
  int within = 0;
  std::vector<bool> resolved;
  for (int i = 0; i < axis.bins; ++i) {
    const double lo = axis.edge(i), hi = axis.edge(i + 1);
    const auto k = static_cast<std::size_t>(i);
    c.rho_lo.push_back(lo);
    c.rho_hi.push_back(hi);
    c.monte_carlo.push_back(fluence->mean[k]);
    c.monte_carlo_stderr.push_back(fluence->stderr_of_mean[k]);
    const double volume = 4.0 / 3.0 * pi * (hi * hi * hi - lo * lo * lo);
    const double expected_collisions = c.exact[k] * volume * static_cast<double>(settings.photons);
    resolved.push_back(expected_collisions >= 100.0 && c.monte_carlo_stderr.back() > 0.0);
    if (resolved.back()) {
      const double z = (c.monte_carlo.back() - c.exact[k]) / c.monte_carlo_stderr.back();
      c.max_abs_z = std::max(c.max_abs_z, std::abs(z));
      within += std::abs(z) < 3.0;
      ++c.compared_shells;
    }
  }
  c.within_3_sigma = c.compared_shells ? static_cast<double>(within) / c.compared_shells : 0.0;
  c.monte_carlo_error =
      relative_error(c.monte_carlo, c.exact, c.rho_hi, settings.near_limit, resolved);
  c.diffusion_error = relative_error(c.diffusion, c.exact, c.rho_hi, settings.near_limit);
  c.grosjean_error = relative_error(c.grosjean, c.exact, c.rho_hi, settings.near_limit);
  return c;
}

}  // namespace scatterlab
