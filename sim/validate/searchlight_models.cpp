#include "searchlight_models.hpp"

#include <fmt/format.h>

#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/validate/half_space_comparison.hpp"

namespace scatterlab {
namespace {

std::string orders(ModelPart part) {
  switch (part) {
    case ModelPart::single: return "once-scattered light";
    case ModelPart::multiple: return "light scattered at least twice";
    case ModelPart::all: return "all scattered light";
  }
  return "";
}

// A model the run's conditions leave out, said in the file instead of left unwritten.
ModelResult not_evaluated(const std::string& model, const std::string& why) {
  return {model, "", {}, {}, "", why, {}, {}};
}

}  // namespace

std::vector<ModelResult> searchlight_model_curves(const HalfSpaceSpec& spec,
                                                  double specular_reflectance, bool with_fluence) {
  std::vector<ModelResult> models;
  const char* diffusion[] = {"dipole", "better_dipole", "quantized_diffusion",
                             "photon_beam_diffusion", "scatterlab_grosjean_beam"};
  if (spec.incidence_deg != 0.0) {
    const std::string why = fmt::format(
        "not evaluated: defined for normal incidence only, and this run's beam arrives at {} deg",
        spec.incidence_deg);
    models.push_back(not_evaluated("single_scatter", why));
    for (const char* model : diffusion) models.push_back(not_evaluated(model, why));
    return models;
  }
  const std::vector<double> r = spec.grid.r.edges();
  const std::size_t nr = r.size() - 1;
  const std::string area_units = fmt::format("W {}^-2 per W incident", spec.medium.length_unit);
  if (!(spec.eta >= 0.5 && spec.eta <= 2.5)) {
    // The exact once-scattered solution holds for any eta; the diffusion models' Fresnel-moment
    // fits only in [0.5, 2.5] (models/boundary_reflection.hpp).
    const SingleScatterReflectance single =
        half_space_single_scatter_reflectance(spec.medium, spec.eta, r, 1e-8);
    models.push_back({"single_scatter", "reflectance_single", {"r"}, {nr}, area_units,
                      "single_scatter R_d(r) of the once-scattered light, annulus average per "
                      "unit incident power",
                      single.mean, single.error});
    models.push_back({"single_scatter", "diffuse_reflectance_single", {}, {}, "W per W incident",
                      "single_scatter total diffuse reflectance of the once-scattered light",
                      {single.total}, {single.total_error}});
    for (const char* model : diffusion) {
      models.push_back(not_evaluated(
          model, fmt::format("not evaluated: its boundary fits hold for eta in [0.5, 2.5], and "
                             "this run's eta is {}",
                             spec.eta)));
    }
    return models;
  }
  const HalfSpaceMedium medium{spec.medium.sigma_a(), spec.medium.sigma_s(), spec.medium.g,
                               spec.eta};
  const std::vector<double> z =
      spec.tallies.fluence && with_fluence ? spec.grid.z.edges() : std::vector<double>{};
  const HalfSpaceComparison comparison =
      compare_half_space(medium, 1.0 - specular_reflectance, r, z);
  for (const ModelCurve& curve : comparison.reflectance) {
    if (curve.model.ends_with("+single_scatter")) continue;  // a sum of two curves written here
    const std::string suffix = tally_suffix(curve.part);
    models.push_back({curve.model, "reflectance" + suffix, {"r"}, {nr}, area_units,
                      fmt::format("{} R_d(r) of the {}, annulus average per unit incident power",
                                  curve.model, orders(curve.part)),
                      curve.values, curve.error});
    ModelResult total{curve.model, "diffuse_reflectance" + suffix, {}, {}, "W per W incident",
                      fmt::format("{} total diffuse reflectance R_dr of the {}", curve.model,
                                  orders(curve.part)),
                      {curve.total}, {}};
    if (!curve.error.empty()) total.error = {curve.total_error};
    models.push_back(total);
  }
  for (const ModelCurve& curve : comparison.fluence) {
    models.push_back({curve.model, "fluence" + tally_suffix(curve.part), {"r", "z"},
                      {nr, z.size() - 1}, area_units,
                      fmt::format("{} phi(r, z) of the {}, cell average per unit incident power",
                                  curve.model, orders(curve.part)),
                      curve.values, {}});
  }
  return models;
}

}  // namespace scatterlab
