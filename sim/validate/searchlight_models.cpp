#include "scatterlab/validate/searchlight_models.hpp"

#include <fmt/format.h>

#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/validate/half_space_comparison.hpp"

namespace scatterlab {
namespace {

constexpr const char* kUnits = "W mfp^-2 per W incident";

ModelResult scalar(const std::string& model, const std::string& name, double value,
                   const std::string& description, double error = -1.0) {
  ModelResult m{model, name, {}, {}, "W per W incident", description, {value}, {}};
  if (error >= 0.0) m.error = {error};
  return m;
}

}  // namespace

std::vector<ModelResult> searchlight_model_curves(const SearchlightSpec& spec,
                                                  double specular_reflectance,
                                                  bool with_fluence) {
  std::vector<ModelResult> models;
  if (spec.incidence_deg != 0.0) return models;
  const std::vector<double> r = spec.grid.r.edges();
  const std::size_t nr = r.size() - 1;

  // The exact once-scattered light: only what left after exactly one scattering event, the
  // reference of the Monte Carlo reflectance_single tally.
  const SingleScatterReflectance single =
      half_space_single_scatter_reflectance(spec.medium, spec.eta, r, 1e-8);
  models.push_back({"single_scatter", "reflectance_single", {"r"}, {nr}, kUnits,
                    "exact once-scattered R_1(r), annulus average (Walter et al. 2009 solver on "
                    "the flat boundary, adaptive quadrature over depth; _error: its estimate)",
                    single.mean, single.error});
  models.push_back(scalar("single_scatter", "diffuse_reflectance_single", single.total,
                          "exact once-scattered total reflectance", single.total_error));

  if (!(spec.eta >= 0.5 && spec.eta <= 2.5)) return models;
  const HalfSpaceMedium medium =
      HalfSpaceMedium::from_albedo(spec.medium.albedo, spec.medium.g, spec.eta);
  const std::vector<double> z =
      spec.tallies.fluence && with_fluence ? spec.grid.z.edges() : std::vector<double>{};
  const HalfSpaceComparison comparison =
      compare_half_space(medium, 1.0 - specular_reflectance, r, z);
  for (const ModelCurve& curve : comparison.reflectance) {
    models.push_back({curve.model, "reflectance", {"r"}, {nr}, kUnits,
                      fmt::format("{} R_d(r), annulus average, times the entry transmittance",
                                  curve.model),
                      curve.values, {}});
    models.push_back(scalar(curve.model, "diffuse_reflectance", curve.total,
                            fmt::format("{} total diffuse reflectance R_dr", curve.model)));
  }
  for (const ModelCurve& curve : comparison.fluence) {
    models.push_back({curve.model, "fluence", {"r", "z"}, {nr, z.size() - 1}, kUnits,
                      fmt::format("{} phi(r, z), cell average, times the entry transmittance",
                                  curve.model),
                      curve.values, {}});
  }
  return models;
}

}  // namespace scatterlab
