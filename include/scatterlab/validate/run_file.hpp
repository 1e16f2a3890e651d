#pragma once
// A finished run's file, written one way for every caller (scatterlab simulate and searchlight,
// and the Python module, python/): the spec records the threads that ran, not "all cores"; the
// provenance names the command; the models that belong beside the run's tallies go under /models
// (point_source_models.hpp for the infinite medium, searchlight_models.hpp for the half-space).
// It returns the model curves it wrote (none for the sphere and the slab), for a summary.

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/transport/engine.hpp"

namespace scatterlab {

// A scene's run of any geometry. `model_fluence`: also each diffusion model's phi(r, z) beside a
// half-space's fluence (searchlight_model_curves; refused by the caller elsewhere).
std::vector<ModelResult> write_run_result(const std::filesystem::path& path, SceneSpec& spec,
                                          const TransportOutput& out, const std::string& command,
                                          bool model_fluence);

}  // namespace scatterlab
