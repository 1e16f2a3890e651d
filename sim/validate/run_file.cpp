#include "scatterlab/validate/run_file.hpp"

#include <variant>

#include "point_source_models.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"
#include "searchlight_models.hpp"

namespace scatterlab {
namespace {

// The models that belong beside a geometry's tallies: the point source's and the half-space's;
// none for the others.
std::vector<ModelResult> model_curves(const InfiniteMediumSpec& spec, const TransportOutput& out,
                                      bool) {
  return point_source_model_curves(spec, out.tallies);
}

std::vector<ModelResult> model_curves(const HalfSpaceSpec& spec, const TransportOutput& out,
                                      bool model_fluence) {
  return searchlight_model_curves(
      spec, scalar_estimate(out.tallies, "specular_reflectance").mean, model_fluence);
}

template <class Spec>
std::vector<ModelResult> model_curves(const Spec&, const TransportOutput&, bool) {
  return {};
}

}  // namespace

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SceneSpec& spec,
                                          const TransportOutput& out, const std::string& command,
                                          bool model_fluence) {
  const std::vector<ModelResult> models = std::visit(
      [&](auto& s) {
        s.run.threads = out.threads;
        return model_curves(s, out, model_fluence);
      },
      spec);
  write_simulation_file(path, spec, out.tallies, run_provenance(out, command), models);
  return models;
}

}  // namespace scatterlab
