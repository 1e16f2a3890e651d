#pragma once
// A finished run's file, written one way for every caller (scatterlab simulate and searchlight,
// and the Python module, python/): the spec records the threads that ran, not "all cores"; the
// provenance names the command; the models that belong beside the run's tallies go under /models
// (point_source_models.hpp for the infinite medium, searchlight_models.hpp for the half-space).
// Each returns the model curves it wrote (none for the sphere and the slab), for a summary.

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SimulationSpec& spec,
                                          const TransportOutput& out, const std::string& command);

// `model_fluence`: also each diffusion model's phi(r, z) (searchlight_model_curves).
std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SearchlightSpec& spec,
                                          const TransportOutput& out, const std::string& command,
                                          bool model_fluence);

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, LitObjectSpec& spec,
                                          const TransportOutput& out, const std::string& command);

std::vector<ModelResult> write_run_result(const std::filesystem::path& path, LayeredSlabSpec& spec,
                                          const TransportOutput& out, const std::string& command);

// A scene's run of any geometry, by the overload of its geometry (`model_fluence`: the
// half-space's; refused by the caller elsewhere).
std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SceneSpec& spec,
                                          const TransportOutput& out, const std::string& command,
                                          bool model_fluence);

}  // namespace scatterlab
