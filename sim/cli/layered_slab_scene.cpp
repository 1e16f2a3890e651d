#include "layered_slab_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string_view>

#include "checkpointed_run.hpp"
#include "prepare_outputs.hpp"
#include "run_figures.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/validate/run_file.hpp"

namespace scatterlab::cli {
namespace {

// simulate's flags that mean something for a slab; any other given is refused.
constexpr std::array<std::string_view, 14> kSlabFlags = {"SCENE",
                                                         "--scene",
                                                         "--out",
                                                         "--photons",
                                                         "--batches",
                                                         "--seed",
                                                         "--threads",
                                                         "--escape-radius",
                                                         "--split-orders",
                                                         "--checkpoint",
                                                         "--checkpoint-interval",
                                                         "--resume",
                                                         "--log-interval",
                                                         "--memory-limit"};

void refuse_other_flags(const CLI::App& command, const std::string& scene) {
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0) continue;
    const std::string name = option->get_name();
    if (name == "--help") continue;
    if (std::find(kSlabFlags.begin(), kSlabFlags.end(), name) != kSlabFlags.end()) continue;
    throw InputError(name,
                     fmt::format("is not for a slab scene ({} has geometry.type = \"slab\"; set "
                                 "the layers in the file)",
                                 scene),
                     "--photons, --batches, --seed, --threads, --escape-radius, "
                     "--split-orders, --out, the checkpoint flags and --log-interval");
  }
}

void print_summary(const LayeredSlabSpec& spec, const TransportOutput& out,
                   const std::string& path) {
  fmt::print("scatterlab simulate: slab of {} layers ({}), n above {}, below {}, {} weighting\n",
             spec.layers.size(), spec.length_unit, spec.n_above, spec.n_below,
             to_string(spec.weighting));
  print_run_time(out);
  print_energy_balance(out, slab_energy_tallies);
  print_figures_of_merit(out, {"diffuse_reflectance", "total_transmittance", "absorbed"});
  fmt::print("  wrote {}: R_d and T_t by r and angle, A by layer, depth and (r, z)\n", path);
}

}  // namespace

int run_layered_slab_scene(CLI::App& command, const SlabFlags& flags,
                           const LongRunOptions& long_run_options, double log_interval,
                           const std::string& command_line, World& world) {
  refuse_other_flags(command, flags.scene);
  const LayeredSlabScene scene = load_layered_slab_scene(flags.scene, Validation::by_caller);
  LayeredSlabSpec spec = scene.spec;
  if (command.get_option("--split-orders")->count() > 0) spec.split_by_order = flags.split_orders;
  apply_run_options(command, flags.run, spec.run);
  spec.validate();
  check_transport_memory(transport_problem(spec), world.size(), long_run_options.resume);
  const std::filesystem::path output =
      prepare_scene_outputs(command, flags.scene, flags.out, scene.output_path, "slab.h5",
                            long_run_options, world.is_root());

  return run_with_checkpoints(
      "simulate", long_run_options, output, fingerprint(spec), spec.run.batches, log_interval,
      world,
      [&spec](const ProgressCallback& progress, const RunControl& control) {
        return run_layered_slab(spec, progress, control);
      },
      [&](const std::filesystem::path& path, const TransportOutput& out) {
        write_run_result(path, spec, out, command_line);
        print_summary(spec, out, path.string());
      });
}

}  // namespace scatterlab::cli
