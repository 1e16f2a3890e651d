#pragma once
// scatterlab simulate on a layered-slab scene (geometry.type = "slab"; io/scene.hpp,
// transport/layered_slab.hpp): the scene read strictly, the run's flags laid over it, one run
// (checkpoints, --resume and interruption as for every run), one file, and the summary with the
// energy balance. Flags of the infinite medium's medium, grid, source and tallies are refused,
// naming the flag: a slab's layers are set in the file.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "long_run.hpp"
#include "run_options.hpp"
#include "scatterlab/parallel/world.hpp"

namespace scatterlab::cli {

// The slab's totals, as its summaries print them (simulate, mcml): with analog absorption every
// photon ends in exactly one of them.
inline const std::vector<std::string> slab_energy_tallies = {
    "specular_reflectance", "diffuse_reflectance", "total_transmittance", "absorbed"};

// The flags simulate shares with a slab scene.
struct SlabFlags {
  std::string scene, out;
  RunOptions run;
  bool split_orders = false;
};

int run_layered_slab_scene(CLI::App& command, const SlabFlags& flags,
                           const LongRunOptions& long_run, double log_interval,
                           const std::string& command_line, World& world);

}  // namespace scatterlab::cli
