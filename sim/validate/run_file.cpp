#include "scatterlab/validate/run_file.hpp"

#include <type_traits>
#include <variant>

#include "point_source_models.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"
#include "searchlight_models.hpp"

namespace scatterlab {

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SimulationSpec& spec,
                                          const TransportOutput& out, const std::string& command) {
  spec.run.threads = out.threads;
  std::vector<ModelResult> models = point_source_model_curves(spec, out.tallies);
  write_simulation_file(path, spec, out.tallies, run_provenance(out, command), models);
  return models;
}

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SearchlightSpec& spec,
                                          const TransportOutput& out, const std::string& command,
                                          bool model_fluence) {
  spec.run.threads = out.threads;
  std::vector<ModelResult> models = searchlight_model_curves(
      spec, scalar_estimate(out.tallies, "specular_reflectance").mean, model_fluence);
  write_searchlight_file(path, spec, out.tallies, run_provenance(out, command), models);
  return models;
}

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, LitObjectSpec& spec,
                                          const TransportOutput& out, const std::string& command) {
  spec.run.threads = out.threads;
  write_lit_object_file(path, spec, out.tallies, run_provenance(out, command));
  return {};
}

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, LayeredSlabSpec& spec,
                                          const TransportOutput& out, const std::string& command) {
  spec.run.threads = out.threads;
  write_layered_slab_file(path, spec, out.tallies, run_provenance(out, command));
  return {};
}

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SceneSpec& spec,
                                          const TransportOutput& out, const std::string& command,
                                          bool model_fluence) {
  return std::visit(
      [&](auto& s) {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, SearchlightSpec>) {
          return write_run_result(path, s, out, command, model_fluence);
        } else {
          return write_run_result(path, s, out, command);
        }
      },
      spec);
}

}  // namespace scatterlab
