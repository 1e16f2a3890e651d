#include "point_source_models.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "scatterlab/models/point_source_diffusion.hpp"
#include "scatterlab/models/point_source_exact.hpp"
#include "scatterlab/models/point_source_grosjean.hpp"
#include "scatterlab/transport/length_units.hpp"

namespace scatterlab {
namespace {

constexpr const char* model_names[] = {"exact", "diffusion", "grosjean"};

std::string what_it_is(const std::string& model) {
  if (model == "exact") return "exact transport solution";
  if (model == "diffusion") return "classical diffusion";
  return "Grosjean's approximation (uncollided light exact, the rest by diffusion)";
}

// Why the run's conditions leave the models out; empty when they hold.
std::string why_not_evaluated(const InfiniteMediumSpec& spec) {
  if (spec.medium.g != 0.0) {
    return fmt::format(
        "not evaluated: these curves are for isotropic scattering (g = 0), and "
        "this run's g is {}",
        spec.medium.g);
  }
  if (!(spec.medium.albedo < 1.0)) {
    return "not evaluated: these curves need absorption (albedo < 1), and this run's albedo is 1";
  }
  if (std::isfinite(spec.run.escape_radius)) {
    return fmt::format(
        "not evaluated: this run stops photons at its escape radius {} {}, which "
        "the infinite medium of these curves would send back",
        spec.run.escape_radius, spec.medium.length_unit);
  }
  return "";
}

}  // namespace

PointSourceCurves point_source_shell_averages(double albedo, const std::vector<double>& rho_edges) {
  PointSourceCurves curves;
  for (std::size_t i = 0; i + 1 < rho_edges.size(); ++i) {
    const double lo = rho_edges[i], hi = rho_edges[i + 1];
    curves.exact.push_back(point_source_fluence_shell_average(albedo, lo, hi));
    curves.diffusion.push_back(diffusion_point_source_shell_average(albedo, lo, hi));
    curves.grosjean.push_back(grosjean_point_source_shell_average(albedo, lo, hi));
  }
  return curves;
}

std::vector<ModelResult> point_source_model_curves(const InfiniteMediumSpec& spec,
                                                   const std::vector<TallyResult>& tallies) {
  const TallyResult* fluence = find_tally(tallies, "fluence_spherical");
  if (spec.source != SourceKind::point || fluence == nullptr) return {};
  std::vector<ModelResult> models;
  if (const std::string why = why_not_evaluated(spec); !why.empty()) {
    for (const char* model : model_names) models.push_back({model, "", {}, {}, "", why, {}, {}});
    return models;
  }
  // The models are in mfp (sigma_t = 1); the tally is in the run's unit (length_units.hpp).
  const UniformAxis rho = length_axis_in_mfp(spec.grid.rho, mfp_per_length_unit(spec.medium));
  const double to_length_unit = reported_length(spec.medium).factor(Units{1, -2});
  const PointSourceCurves curves = point_source_shell_averages(spec.medium.albedo, rho.edges());
  const std::vector<double>* values[] = {&curves.exact, &curves.diffusion, &curves.grosjean};
  for (std::size_t m = 0; m < 3; ++m) {
    std::vector<double> scaled = *values[m];
    for (double& value : scaled) value *= to_length_unit;
    models.push_back({model_names[m],
                      "fluence_spherical",
                      fluence->dims,
                      fluence->shape,
                      fluence->units,
                      what_it_is(model_names[m]) +
                          " phi(rho) of an isotropic point source in an infinite medium with "
                          "isotropic scattering, shell average per unit source power",
                      std::move(scaled),
                      {}});
  }
  return models;
}

}  // namespace scatterlab
