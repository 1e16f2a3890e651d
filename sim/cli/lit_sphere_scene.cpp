#include "lit_sphere_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <optional>
#include <string_view>

#include "checkpointed_run.hpp"
#include "prepare_outputs.hpp"
#include "run_figures.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/validate/run_file.hpp"
#ifdef SCATTERLAB_WITH_RENDER
#include "scatterlab/mesh/lit_mesh.hpp"
#include "scatterlab/render/render_scene.hpp"
#endif

namespace scatterlab::cli {
namespace {

// simulate's flags that mean something for a sphere; any other given is refused.
constexpr std::array<std::string_view, 18> kSphereFlags = {
    "SCENE",         "--scene",        "--out",        "--albedo",
    "--g",           "--sigma-t",      "--material",   "--channel",
    "--length-unit", "--photons",      "--batches",    "--seed",
    "--threads",     "--split-orders", "--checkpoint", "--checkpoint-interval",
    "--resume",      "--log-interval"};

void refuse_other_flags(const CLI::App& command, const std::string& scene) {
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0) continue;
    const std::string name = option->get_name();
    if (name == "--memory-limit" || name == "--help") continue;
    if (std::find(kSphereFlags.begin(), kSphereFlags.end(), name) != kSphereFlags.end()) continue;
    throw InputError(name,
                     fmt::format("is not for a lit object's scene ({} has geometry.type "
                                 "\"sphere\" or \"mesh\"; set the object in the file)",
                                 scene),
                     "the medium's flags, --photons, --batches, --seed, --threads, "
                     "--split-orders, --out, the checkpoint flags and --log-interval");
  }
}

LitSphereSpec sphere_spec(const CLI::App& command, const SphereFlags& flags,
                          const LitSphereScene& scene) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  LitSphereSpec spec = scene.spec;
  const std::optional<double> material_eta =
      apply_medium_options(command, flags.medium, flags.albedo, flags.g, flags.sigma_t,
                           scene.material, spec.medium, spec.material);
  // A material brings its table's index unless the scene gives one.
  if (material_eta && !scene.eta_given) spec.eta = *material_eta;
  if (given("--split-orders")) spec.split_by_order = flags.split_orders;
  apply_run_options(command, flags.run, spec.run);
  spec.validate();
  return spec;
}

void print_summary(const LitSphereSpec& spec, const TransportOutput& out, const std::string& path) {
  const std::string object =
      spec.mesh ? fmt::format("mesh ({}, in {})", spec.mesh_source, spec.medium.length_unit)
                : fmt::format("sphere of radius {} {}", spec.radius, spec.medium.length_unit);
  fmt::print("scatterlab simulate: {}, {} light, albedo {}, g {}, eta {}\n", object,
             to_string(spec.light), spec.medium.albedo, spec.medium.g, spec.eta);
  if (spec.material) {
    fmt::print("  material {} ({}), {} channel\n", spec.material->name, spec.material->library,
               spec.material->channel);
  }
  print_run_time(out);
  // Each photon ends in exactly one of these: they sum to 1 photon by photon.
  print_energy_balance(out, {"reflected_at_entry", "exited", "absorbed"});
  print_figures_of_merit(out, {"exited", "absorbed", "exitance"});
  if (spec.mesh) {
    fmt::print("  wrote {}: exitance [{}] per triangle\n", path, spec.mesh->triangle_count());
  } else {
    fmt::print("  wrote {}: exitance [{}] against the angle from the lit pole\n", path,
               spec.psi.bins);
  }
}

// A mesh scene's object, read as render reads its [mesh] table; without the renderer's
// libraries (Embree, tinyobjloader) there is no mesh to run.
void load_mesh(const std::string& scene, LitSphereSpec& spec) {
#ifdef SCATTERLAB_WITH_RENDER
  SceneMesh mesh = load_scene_mesh(scene);
  spec.mesh_source = std::move(mesh.source);
  spec.mesh = std::make_shared<const TriangleMesh>(std::move(mesh.mesh));
#else
  (void)spec;
  throw InputError(
      "geometry.type",
      fmt::format("is \"mesh\" in {}, but this build of scatterlab has no renderer", scene),
      "a build with Embree, tinyobjloader, OpenEXR and libpng: install them, then "
      "configure and build again");
#endif
}

TransportOutput run_object(const LitSphereSpec& spec, const ProgressCallback& progress,
                           const RunControl& control) {
#ifdef SCATTERLAB_WITH_RENDER
  if (spec.mesh) return run_lit_mesh(spec, progress, control);
#endif
  return run_lit_sphere(spec, progress, control);
}

}  // namespace

int run_lit_sphere_scene(CLI::App& command, const SphereFlags& flags,
                         const LongRunOptions& long_run_options, double log_interval,
                         const std::string& command_line, World& world) {
  refuse_other_flags(command, flags.scene);
  LitSphereScene scene = load_lit_sphere_scene(flags.scene, Validation::by_caller);
  if (scene.mesh) load_mesh(flags.scene, scene.spec);
  LitSphereSpec spec = sphere_spec(command, flags, scene);
#ifdef SCATTERLAB_WITH_RENDER
  if (spec.mesh) check_lit_mesh(spec);
#endif
  check_transport_memory(transport_problem(spec), world.size(), long_run_options.resume);
  const std::filesystem::path output =
      prepare_scene_outputs(command, flags.scene, flags.out, scene.output_path, "lit-sphere.h5",
                            long_run_options, world.is_root());

  return run_with_checkpoints(
      "simulate", long_run_options, output, fingerprint(spec), spec.run.batches, log_interval,
      world,
      [&spec](const ProgressCallback& progress, const RunControl& control) {
        return run_object(spec, progress, control);
      },
      [&](const std::filesystem::path& path, const TransportOutput& out) {
        write_run_result(path, spec, out, command_line);
        print_summary(spec, out, path.string());
      });
}

}  // namespace scatterlab::cli
