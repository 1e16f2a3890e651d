// scatterlab searchlight: a pencil beam on a semi-infinite medium behind a refractive interface
// (Bitterli 2013, §2.3 and Alg. 1), from flags, written to one HDF5 file.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include "checkpointed_run.hpp"
#include "commands.hpp"
#include "log_interval_option.hpp"
#include "long_run.hpp"
#include "medium_options.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "run_figures.hpp"
#include "run_options.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/models/chandrasekhar_h.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/validate/run_file.hpp"
#include "scene_option.hpp"

namespace scatterlab::cli {
namespace {

// Every flag, starting at the built-in default (a default SearchlightSpec's), which --help shows;
// only the flags given override the scene.
struct SearchlightOptions {
  std::string scene, out = "searchlight.h5", tallies;
  double albedo = 0, g = 0, sigma_t = 0, eta = 0, incidence = 0;
  RunOptions run;        // --photons, --batches, --seed, --threads, --escape-radius
  MediumOptions medium;  // --material, --channel, --length-unit
  double r_max = 0, z_max = 0;
  int r_bins = 0, z_bins = 0, theta_bins = 0;
  bool no_fluence = false;
  bool model_fluence = false;
};

// --tallies names the optional tallies, as simulate's does; the surface tallies (R_d(r), the
// exitant radiance and the totals) cost one bin lookup per exit and are always on.
std::string tally_list(const SearchlightTallies& tallies) {
  return tallies.fluence ? "fluence" : "none";
}

void apply_tally_list(const std::string& list, SearchlightTallies& tallies) {
  if (list != "fluence" && list != "none") {
    throw InputError("--tallies", fmt::format("got \"{}\"", list),
                     "fluence or none (R_d(r), the exitant radiance and the totals are always "
                     "tallied)");
  }
  tallies.fluence = list == "fluence";
}

SearchlightOptions default_options() {
  const SearchlightSpec spec;
  SearchlightOptions o;
  o.tallies = tally_list(spec.tallies);
  o.albedo = spec.medium.albedo;
  o.g = spec.medium.g;
  o.sigma_t = spec.medium.sigma_t;
  o.medium.length_unit = spec.medium.length_unit;
  o.eta = spec.eta;
  o.incidence = spec.incidence_deg;
  o.run = run_options_of(spec.run);
  o.r_max = spec.grid.r.max;
  o.z_max = spec.grid.z.max;
  o.r_bins = spec.grid.r.bins;
  o.z_bins = spec.grid.z.bins;
  o.theta_bins = spec.grid.theta_o.bins;
  return o;
}

void print_summary(const SearchlightSpec& spec, const SearchlightOutput& out,
                   const std::vector<ModelResult>& models, const std::string& path) {
  fmt::print("scatterlab searchlight: half-space, albedo {}, g {}, eta {}, incidence {} deg\n",
             spec.medium.albedo, spec.medium.g, spec.eta, spec.incidence_deg);
  if (spec.material) {
    fmt::print("  material {} ({}), {} channel: sigma_t {:.6g} / {}, lengths in {}\n",
               spec.material->name, spec.material->library, spec.material->channel,
               spec.medium.sigma_t, spec.medium.length_unit, spec.medium.length_unit);
  }
  print_run_time(out);
  // The escaped power is a tally only with a finite escape radius.
  print_energy_balance(out, {"specular_reflectance", "diffuse_reflectance", "absorbed", "escaped"});
  print_figures_of_merit(out, {"diffuse_reflectance", "absorbed", "reflectance", "fluence"});
  fmt::print("  once-scattered part of the diffuse reflectance: {}\n",
             estimate_text(scalar_estimate(out.tallies, "diffuse_reflectance_single")));
  // The one case with an exact total: index-matched, isotropic (chandrasekhar_h.hpp).
  if (spec.eta == 1.0 && spec.medium.g == 0.0) {
    const double mu0 = std::cos(spec.incidence_deg * std::numbers::pi / 180.0);
    fmt::print(
        "  exact diffuse reflectance for this index-matched isotropic medium: {:.6f} "
        "(1 - H(mu0) sqrt(1 - albedo), Chandrasekhar)\n",
        half_space_diffuse_reflectance(spec.medium.albedo, mu0));
  }
  // Each model's total next to the Monte Carlo total it predicts.
  for (const ModelResult& m : models) {
    if (m.values.empty()) {
      fmt::print("  {:<24} {}\n", m.model, m.description);
      continue;
    }
    if (!m.shape.empty()) continue;
    const ScalarEstimate mc = scalar_estimate(out.tallies, m.name);
    const std::string sigma = sigma_text(mc, m.values[0]);
    fmt::print("  {:<24} {:<28} {:.6f}   Monte Carlo {}{}{}\n", m.model, m.name, m.values[0],
               estimate_text(mc), sigma.empty() ? "" : " ", sigma);
  }
  fmt::print("  wrote {}\n", path);
}

int run_searchlight_command(CLI::App& command, const SearchlightOptions& o,
                            const LongRunOptions& long_run_options, double log_interval,
                            const std::string& command_line, World& world) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  SearchlightScene scene;
  // The file read strictly (keys, types), the flags over it, then the whole validated below.
  if (given("--scene")) scene = load_searchlight_scene(o.scene, Validation::by_caller);
  SearchlightSpec& spec = scene.spec;
  const std::optional<double> material_eta = apply_medium_options(
      command, o.medium, o.albedo, o.g, o.sigma_t, scene.material, spec.medium, spec.material);
  // A material brings its table's index unless the scene or --eta gives one.
  if (material_eta && !scene.eta_given) spec.eta = *material_eta;
  if (given("--eta")) spec.eta = o.eta;
  if (given("--incidence")) spec.incidence_deg = o.incidence;
  apply_run_options(command, o.run, spec.run);
  if (given("--r-max")) spec.grid.r.max = o.r_max;
  if (given("--r-bins")) spec.grid.r.bins = o.r_bins;
  if (given("--z-max")) spec.grid.z.max = o.z_max;
  if (given("--z-bins")) spec.grid.z.bins = o.z_bins;
  if (given("--theta-bins")) spec.grid.theta_o.bins = o.theta_bins;
  if (given("--tallies")) apply_tally_list(o.tallies, spec.tallies);
  if (given("--no-fluence")) spec.tallies.fluence = false;
  spec.validate();
  // The models' phi(r, z) goes beside the Monte Carlo's: without it there is nothing to model.
  if (o.model_fluence && !spec.tallies.fluence) {
    throw InputError("--model-fluence",
                     given("--no-fluence") || given("--tallies")
                         ? "given without the fluence tally (--tallies none, --no-fluence)"
                         : "given with the scene's tallies.fluence = false",
                     "--model-fluence with the fluence tally on (--tallies fluence)");
  }
  check_transport_memory(transport_problem(spec), world.size(), long_run_options.resume);

  const std::filesystem::path path =
      prepare_scene_outputs(command, given("--scene") ? o.scene : "", o.out, scene.output_path,
                            "searchlight.h5", long_run_options, world.is_root());

  // Ranks, checkpoints, --resume and interruption, as for simulate (long_run.hpp).
  return run_with_checkpoints(
      "searchlight", long_run_options, path, fingerprint(spec), spec.run.batches, log_interval,
      world,
      [&spec](const ProgressCallback& progress, const RunControl& control) {
        return run_searchlight(spec, progress, control);
      },
      [&](const std::filesystem::path& written, const TransportOutput& out) {
        const std::vector<ModelResult> models =
            write_run_result(written, spec, out, command_line, o.model_fluence);
        print_summary(spec, out, models, written.string());
      });
}

}  // namespace

Action add_searchlight_command(CLI::App& app, const std::string& command_line, World& world) {
  auto* command = app.add_subcommand(
      "searchlight",
      "Pencil beam on a semi-infinite medium z > 0 behind a smooth interface of relative index "
      "eta (Bitterli 2013, §2.3): diffuse reflectance R_d(r), exitant radiance L(r, theta_o), "
      "fluence phi(r, z) and the totals, each split by scattering order, with standard errors, "
      "to HDF5. Without flags: albedo 0.99, g 0, eta 1.3, normal incidence.");
  auto o = std::make_shared<SearchlightOptions>(default_options());
  command->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  command->add_option("--out", o->out,
                      "Output HDF5 file (default: the scene's output.path when it has one)");
  command->add_option("--albedo", o->albedo, "Single-scattering albedo in [0, 1]");
  command->add_option("--g", o->g, "Henyey-Greenstein mean cosine, |g| < 1");
  command->add_option("--sigma-t", o->sigma_t, "Extinction coefficient in 1/length-unit");
  add_medium_options(*command, o->medium);
  command->add_option("--eta", o->eta,
                      "Relative index n_medium / n_outside, in [0.1, 10]; 1 for no interface; "
                      "with a material, its table's value unless given");
  command->add_option("--incidence", o->incidence,
                      "Beam angle from the surface normal, degrees in [0, 90)");
  add_run_options(*command, o->run);
  command->add_option("--r-max", o->r_max, "Radial grid extent, in the length unit");
  command->add_option("--r-bins", o->r_bins, "Radial bins");
  command->add_option("--z-max", o->z_max, "Depth grid extent of the fluence, in the length unit");
  command->add_option("--z-bins", o->z_bins, "Depth bins of the fluence");
  command->add_option("--theta-bins", o->theta_bins, "Exit-angle bins over [0, pi/2]");
  CLI::Option* tallies = command->add_option(
      "--tallies", o->tallies,
      "fluence or none: the fluence phi(r, z) costs a bin lookup at every event; R_d(r), the "
      "exitant radiance and the totals are always tallied");
  command->add_flag("--model-fluence", o->model_fluence,
                    "Also write each diffusion model's phi(r, z) under /models (about 1 ms per "
                    "cell and model: a minute on the default grid); needs the fluence tally");
  command->add_flag("--no-fluence", o->no_fluence, "Same as --tallies none")->excludes(tallies);
  const auto long_run = add_long_run_options(*command);
  add_memory_limit_option(*command);
  const auto log_interval = add_log_interval_option(*command);
  // Last, so that a bad value of a flag is reported before the positional file it spilled into.
  add_scene_option(*command, o->scene, "data/scenes/searchlight.toml");
  return [command, o, long_run, log_interval, command_line, &world] {
    return run_searchlight_command(*command, *o, *long_run, *log_interval, command_line, world);
  };
}

}  // namespace scatterlab::cli
