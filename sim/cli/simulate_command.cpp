// scatterlab simulate: a pencil beam or point source in an infinite medium (Vavassori §4.1),
// from a scene file and/or flags, written to one HDF5 file.
#include <fmt/format.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "checkpointed_run.hpp"
#include "commands.hpp"
#include "layered_slab_scene.hpp"
#include "lit_sphere_scene.hpp"
#include "log_interval_option.hpp"
#include "long_run.hpp"
#include "medium_options.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "run_figures.hpp"
#include "run_options.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/output_plan.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/parallel/world.hpp"
#include "scatterlab/transport/simulate.hpp"
#include "scatterlab/validate/run_file.hpp"
#include "scene_option.hpp"

namespace scatterlab::cli {
namespace {

// Every flag, starting at the built-in default (a default SimulationSpec's), which --help shows;
// only the flags given override the scene.
struct SimulateOptions {
  std::string scene, out = "scatterlab.h5", out_dir, source, estimator, tallies;
  double albedo = 0, g = 0, sigma_t = 0;
  RunOptions run;        // --photons, --batches, --seed, --threads, --escape-radius
  MediumOptions medium;  // --material, --channel, --length-unit
  double r_max = 0, z_min = 0, z_max = 0, rho_max = 0;
  int r_bins = 0, z_bins = 0, theta_bins = 0, phi_bins = 0, rho_bins = 0;
  bool fold_phi = false, split_orders = false;
};

// The tallies --tallies names, and the request's switch for each.
const std::map<std::string, bool TallyRequest::*>& tally_names() {
  static const std::map<std::string, bool TallyRequest::*> names = {
      {"radiance", &TallyRequest::radiance},
      {"fluence", &TallyRequest::fluence},
      {"flux", &TallyRequest::flux},
      {"fluence_spherical", &TallyRequest::fluence_spherical}};
  return names;
}

std::string tally_list(const TallyRequest& tallies) {
  std::vector<std::string> on;
  for (const auto& [name, member] : tally_names()) {
    if (tallies.*member) on.push_back(name);
  }
  return fmt::format("{}", fmt::join(on, ","));
}

SimulateOptions default_options() {
  const SimulationSpec spec;
  SimulateOptions o;
  o.source = to_string(spec.source);
  o.estimator = to_string(spec.tallies.estimator);
  o.tallies = tally_list(spec.tallies);
  o.albedo = spec.medium.albedo;
  o.g = spec.medium.g;
  o.sigma_t = spec.medium.sigma_t;
  o.medium.length_unit = spec.medium.length_unit;
  o.run = run_options_of(spec.run);
  const Grid& grid = spec.grid;
  o.r_max = grid.r.max;
  o.z_min = grid.z.min;
  o.z_max = grid.z.max;
  o.rho_max = grid.rho.max;
  o.r_bins = grid.r.bins;
  o.z_bins = grid.z.bins;
  o.theta_bins = grid.theta.bins;
  o.phi_bins = grid.phi.bins;
  o.rho_bins = grid.rho.bins;
  return o;
}

std::string shape_text(const TallyResult& t) {
  std::string text;
  for (std::size_t i = 0; i < t.shape.size(); ++i) {
    text += (i ? " x " : "") + std::to_string(t.shape[i]);
  }
  return text;
}

void print_summary(const SimulationSpec& spec, const SimulationOutput& out,
                   const std::string& path) {
  fmt::print("scatterlab simulate: {} source, albedo {}, g {}, {} estimator\n",
             to_string(spec.source), spec.medium.albedo, spec.medium.g,
             to_string(spec.tallies.estimator));
  if (spec.material) {
    fmt::print("  material {} ({}), {} channel: sigma_t {:.6g} / {}, lengths in {}\n",
               spec.material->name, spec.material->library, spec.material->channel,
               spec.medium.sigma_t, spec.medium.length_unit, spec.medium.length_unit);
  }
  print_run_time(out);
  print_energy_balance(out, {"absorbed", "absorbed_outside_grid", "escaped"});
  // The energy totals, and the volume tallies whose figures differ between the estimators.
  print_figures_of_merit(out, {"absorbed", "escaped", "fluence", "radiance", "fluence_spherical"});
  std::string written;
  for (const TallyResult& t : out.tallies) {
    if (!t.shape.empty())
      written += fmt::format("{}{} [{}]", written.empty() ? "" : ", ", t.name, shape_text(t));
  }
  fmt::print("  wrote {}: {}\n", path, written);
}

void apply_tally_list(const std::string& list, TallyRequest& tallies) {
  for (const auto& [name, member] : tally_names()) tallies.*member = false;
  std::stringstream stream(list);
  std::string name;
  while (std::getline(stream, name, ',')) {
    const auto it = tally_names().find(name);
    if (it == tally_names().end()) {
      throw InputError("--tallies", fmt::format("unknown tally \"{}\"", name),
                       "a comma-separated list of radiance, fluence, flux, fluence_spherical");
    }
    tallies.*(it->second) = true;
  }
}

// The flags given override the scene (or the defaults when there is none).
void apply_flags(CLI::App& command, const SimulateOptions& o,
                 const std::optional<MaterialRequest>& scene_material, SimulationSpec& spec) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  apply_medium_options(command, o.medium, o.albedo, o.g, o.sigma_t, scene_material, spec.medium,
                       spec.material);
  if (given("--source")) {
    spec.set_source(o.source == "point" ? SourceKind::point : SourceKind::pencil_beam);
  }
  if (given("--estimator")) {
    spec.tallies.estimator =
        o.estimator == "collision" ? Estimator::collision : Estimator::track_length;
  }
  if (given("--tallies")) apply_tally_list(o.tallies, spec.tallies);
  if (given("--split-orders")) spec.tallies.split_by_order = o.split_orders;
  apply_run_options(command, o.run, spec.run);
  Grid& grid = spec.grid;
  if (given("--r-max")) grid.r.max = o.r_max;
  if (given("--r-bins")) grid.r.bins = o.r_bins;
  if (given("--z-min")) grid.z.min = o.z_min;
  if (given("--z-max")) grid.z.max = o.z_max;
  if (given("--z-bins")) grid.z.bins = o.z_bins;
  if (given("--theta-bins")) grid.theta.bins = o.theta_bins;
  if (given("--phi-bins")) grid.phi.bins = o.phi_bins;
  if (given("--fold-phi")) grid.set_fold_phi(o.fold_phi);
  if (given("--rho-max")) grid.rho.max = o.rho_max;
  if (given("--rho-bins")) grid.rho.bins = o.rho_bins;
  spec.validate();
}

// A run to do: what, and where its file goes.
struct PlannedRun {
  SimulationSpec spec;
  std::filesystem::path output;
  // Where the path came from, for errors: --out, --out-dir or the scene's output.path.
  std::string output_field;
};

// The runs to do, and the directory that holds their files when there is one.
struct RunPlan {
  std::vector<PlannedRun> runs;
  std::string directory;        // empty: the one run's file is named by --out or the scene
  std::string directory_field;  // --out or --out-dir
};

// One run, or one per combination of a sweep (scene.hpp), each with its output path.
RunPlan plan_runs(CLI::App& command, const SimulateOptions& o, const LongRunOptions& long_run) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  // Each point of the file read strictly (keys, types), the flags over it, then the whole
  // validated (apply_flags).
  std::vector<SweepPoint> points = given("--scene") ? load_sweep(o.scene, Validation::by_caller)
                                                    : std::vector<SweepPoint>{SweepPoint{}};
  const bool sweep = points.size() > 1 || !points.front().label.empty();
  // Many files go into a directory: --out names it for a sweep (as for every command that
  // writes many files); --out-dir is the same directory, for a single run too.
  const std::string out_dir = given("--out-dir") ? o.out_dir : sweep && given("--out") ? o.out : "";
  const std::string dir_field = given("--out-dir") ? "--out-dir" : "--out";
  if (sweep && out_dir.empty()) {
    throw InputError("--out",
                     fmt::format("missing: the scene sweeps {} combinations", points.size()),
                     "--out DIR, a directory for one file per combination (made if missing)");
  }
  if (sweep && !long_run.checkpoint.empty()) {
    throw InputError("--checkpoint", "given with a sweep: every run checkpoints beside its file",
                     "--checkpoint only for a single run");
  }
  RunPlan plan{{}, out_dir, dir_field};
  for (SweepPoint& point : points) {
    apply_flags(command, o, point.scene.material, point.scene.spec);
    std::filesystem::path output;
    std::string field = "--out";
    if (!out_dir.empty()) {
      field = dir_field;
      const std::string name =
          point.label.empty()
              ? std::filesystem::path(point.scene.output_path.value_or("scatterlab.h5"))
                    .filename()
                    .string()
              : point.label + ".h5";
      output = std::filesystem::path(out_dir) / name;
    } else {
      output = given("--out") ? o.out : point.scene.output_path.value_or("scatterlab.h5");
      if (!given("--out") && point.scene.output_path) field = "output.path";
    }
    plan.runs.push_back({point.scene.spec, output, field});
  }
  return plan;
}

int run_one(PlannedRun run, const LongRunOptions& options, double log_interval,
            const std::string& command_line, World& world) {
  SimulationSpec& spec = run.spec;
  return run_with_checkpoints(
      "simulate", options, run.output, fingerprint(spec), spec.run.batches, log_interval, world,
      [&spec](const ProgressCallback& progress, const RunControl& control) {
        return simulate(spec, progress, control);
      },
      [&](const std::filesystem::path& path, const TransportOutput& out) {
        write_run_result(path, spec, out, command_line);
        print_summary(spec, out, path.string());
      });
}

int run_simulate(CLI::App& command, const SimulateOptions& o, const LongRunOptions& long_run,
                 double log_interval, const std::string& command_line, World& world) {
  // A sphere scene runs the lit sphere (lit_sphere_scene.hpp) with the flags that apply to it.
  const std::string geometry =
      command.get_option("--scene")->count() > 0 ? scene_geometry(o.scene) : "infinite";
  if (geometry == "sphere" || geometry == "mesh") {
    const SphereFlags flags{o.scene,   o.out,    o.albedo, o.g,
                            o.sigma_t, o.medium, o.run,    o.split_orders};
    return run_lit_sphere_scene(command, flags, long_run, log_interval, command_line, world);
  }
  // A slab scene runs the layered slab (layered_slab_scene.hpp).
  if (geometry == "slab") {
    const SlabFlags flags{o.scene, o.out, o.run, o.split_orders};
    return run_layered_slab_scene(command, flags, long_run, log_interval, command_line, world);
  }
  const RunPlan run_plan = plan_runs(command, o, long_run);
  const std::vector<PlannedRun>& runs = run_plan.runs;
  const std::string& directory = run_plan.directory;
  // Every run's memory before any starts (engine.hpp): a sweep is refused whole, not halfway.
  for (const PlannedRun& run : runs) {
    check_transport_memory(transport_problem(run.spec), world.size(), long_run.resume);
  }
  OutputPlan plan;
  if (!o.scene.empty()) plan.input("--scene", o.scene);
  if (!directory.empty()) plan.output_directory(run_plan.directory_field, directory);
  for (const PlannedRun& run : runs) {
    plan.output_file(run.output_field, run.output);
    plan.output_file("--checkpoint", checkpoint_path(long_run, run.output));
  }
  // The root makes the directory (prepare_outputs); every rank learns whether its outputs are
  // ready, so that none waits on a root that stopped (a broadcast is a barrier here).
  std::exception_ptr failure;
  try {
    prepare_outputs(plan, world.is_root());
    if (world.is_root()) plan.make_output_directories();
  } catch (const InputError&) {
    failure = std::current_exception();
  }
  const bool ready = world.communicator().broadcast_from_root(failure ? 0 : 1) != 0;
  if (failure) std::rethrow_exception(failure);
  if (!ready) return 2;  // the root said why
  for (const PlannedRun& run : runs) {
    // Runs into a directory (sweeps) skip what is done; the root decides, so that every rank
    // runs the same.
    const bool skip =
        !directory.empty() && world.communicator().broadcast_from_root(
                                  complete_file_of(run.output, fingerprint(run.spec)) ? 1 : 0) != 0;
    if (skip) {
      if (world.is_root())
        fmt::print("skip {}: done already, same parameters\n", run.output.string());
      continue;
    }
    const int status = run_one(run, long_run, log_interval, command_line, world);
    if (status != 0) return status;
  }
  return 0;
}

}  // namespace

std::uint64_t photon_count(double photons) {
  if (!(photons >= 0.0 && photons <= 0x1p63 && photons == std::floor(photons))) {
    throw InputError("run.photons", fmt::format("got {}", photons),
                     "a whole number >= 1 (1e8 is accepted)");
  }
  return static_cast<std::uint64_t>(photons);
}

Action add_simulate_command(CLI::App& app, const std::string& command_line, World& world) {
  auto* command = app.add_subcommand(
      "simulate",
      "Pencil beam (or isotropic point source) in an infinite medium: binned radiance "
      "L(r,z,theta,phi), fluence and vector irradiance with standard errors, to HDF5. Without "
      "flags: the paper's case, g = 0.9, albedo 0.5 (Vavassori §4.1). A scene whose "
      "geometry.type is \"sphere\" runs the lit sphere instead (data/scenes/lit-sphere.toml): "
      "exitance against the angle from the lit pole, per scattering order; one whose "
      "geometry.type is \"slab\" runs a layered slab as MCML does (data/scenes/skin-slab.toml).");
  auto o = std::make_shared<SimulateOptions>(default_options());
  // As in most Unix tools, a repeated flag takes its last value (scripts append overrides).
  command->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  CLI::Option* out = command->add_option(
      "--out", o->out,
      "Output HDF5 file (default: the scene's output.path when it has one); for a sweep (a "
      "scene whose keys hold lists of values), the directory for its files, one per "
      "combination named from its values, at most 1000; done combinations are skipped; the "
      "directory is new, empty or one scatterlab wrote, and made when missing");
  command
      ->add_option("--out-dir", o->out_dir,
                   "Directory for the output file (named from the scene's output.path), or a "
                   "sweep's directory as --out; not with --out")
      ->excludes(out);
  command->add_option("--source", o->source, "Source: beam (along +z) or point (isotropic)")
      ->check(CLI::IsMember({"beam", "point"}));
  command->add_option("--albedo", o->albedo, "Single-scattering albedo in [0, 1]");
  command->add_option("--g", o->g, "Henyey-Greenstein mean cosine, |g| < 1");
  command->add_option("--sigma-t", o->sigma_t, "Extinction coefficient in 1/length-unit");
  add_medium_options(*command, o->medium);
  command->add_option("--estimator", o->estimator, "Estimator of the volume tallies")
      ->check(CLI::IsMember({"collision", "track_length"}));
  command->add_option("--tallies", o->tallies,
                      "Comma-separated: radiance, fluence, flux, fluence_spherical");
  // A flag takes a value too (--split-orders=false), to switch off what a scene switches on.
  command->add_flag("--split-orders", o->split_orders,
                    "Also tally unscattered, once- and multiply-scattered light apart");
  add_run_options(*command, o->run);
  command->add_option("--r-max", o->r_max, "Radial grid extent, in the length unit");
  command->add_option("--r-bins", o->r_bins, "Radial bins");
  command->add_option("--z-min", o->z_min, "Axial grid start, in the length unit");
  command->add_option("--z-max", o->z_max, "Axial grid end, in the length unit");
  command->add_option("--z-bins", o->z_bins, "Axial bins");
  command->add_option("--theta-bins", o->theta_bins, "Polar-angle bins over [0, pi]");
  command->add_option("--phi-bins", o->phi_bins,
                      "Azimuth bins over [0, 2 pi], even; over [0, pi] with --fold-phi");
  command->add_flag("--fold-phi", o->fold_phi, "Fold phi onto [0, pi] (L is even in phi)");
  command->add_option("--rho-max", o->rho_max, "Spherical-shell grid extent, in the length unit");
  command->add_option("--rho-bins", o->rho_bins, "Spherical shells (point source)");
  const auto long_run = add_long_run_options(*command);
  add_memory_limit_option(*command);
  const auto log_interval = add_log_interval_option(*command);
  // Last, so that a bad value of a flag is reported before the positional file it spilled into.
  add_scene_option(*command, o->scene, "data/scenes/paper-beam.toml");
  return [command, o, long_run, log_interval, command_line, &world] {
    return run_simulate(*command, *o, *long_run, *log_interval, command_line, world);
  };
}

}  // namespace scatterlab::cli
