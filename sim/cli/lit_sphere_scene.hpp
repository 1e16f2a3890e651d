#pragma once
// scatterlab simulate on a lit-sphere scene (geometry.type = "sphere"; io/scene.hpp,
// transport/lit_sphere.hpp): the scene read strictly, the flags of the medium and the run laid
// over it, one run (checkpoints, --resume and interruption as for every run), one file, and the
// summary with the energy balance. Flags of the infinite medium's grid, source and tallies are
// refused, naming the flag.

#include <CLI/CLI.hpp>
#include <string>

#include "long_run.hpp"
#include "medium_options.hpp"
#include "run_options.hpp"
#include "scatterlab/parallel/world.hpp"

namespace scatterlab::cli {

// The flags simulate shares with a lit-sphere scene.
struct SphereFlags {
  std::string scene, out;
  double albedo = 0, g = 0, sigma_t = 0;
  MediumOptions medium;
  RunOptions run;
  bool split_orders = false;
};

int run_lit_sphere_scene(CLI::App& command, const SphereFlags& flags,
                         const LongRunOptions& long_run, double log_interval,
                         const std::string& command_line, World& world);

}  // namespace scatterlab::cli
