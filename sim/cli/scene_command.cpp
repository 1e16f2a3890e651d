// scatterlab simulate (and searchlight, its convenience for the half-space): one scene of any
// geometry (io/scene.hpp), or a sweep of them, from a file and/or flags; each run checkpointed,
// resumable and written to one HDF5 file, with a summary. The one path every geometry takes:
// read (the geometry chosen once) -> flags laid over each point -> validate -> memory of every
// run -> outputs planned -> runs.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

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
#include "scatterlab/core/work_pace.hpp"
#include "scatterlab/io/output_plan.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/scene_schema.hpp"
#include "scatterlab/io/simulation_file.hpp"
#include "scatterlab/models/chandrasekhar_h.hpp"
#include "scatterlab/parallel/world.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"
#include "scatterlab/transport/simulate.hpp"
#include "scatterlab/validate/run_file.hpp"
#include "scene_option.hpp"
#ifdef SCATTERLAB_WITH_RENDER
#include "scatterlab/mesh/lit_mesh.hpp"
#include "scatterlab/render/render_scene.hpp"
#endif

namespace scatterlab::cli {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};

// Every flag of every geometry; --help shows the built-in defaults of the command's own
// geometry. Only the flags given override the scene, and only those its geometry takes.
struct SceneOptions {
  std::string scene, out, out_dir, source, estimator, tallies;
  double albedo = 0, g = 0, sigma_t = 0, eta = 0, incidence = 0;
  RunOptions run;        // --photons, --batches, --seed, --threads, --escape-radius
  MediumOptions medium;  // --material, --channel, --length-unit
  double r_max = 0, z_min = 0, z_max = 0, rho_max = 0;
  int r_bins = 0, z_bins = 0, theta_bins = 0, phi_bins = 0, rho_bins = 0;
  bool fold_phi = false, split_orders = false, no_fluence = false, model_fluence = false;
};

// The flags every geometry takes: the scene, the outputs, the long run's and the budget's.
constexpr std::string_view kCommonFlags[] = {"SCENE",     "--scene",        "--out",
                                             "--out-dir", "--checkpoint",   "--checkpoint-interval",
                                             "--resume",  "--log-interval", "--memory-limit",
                                             "--help"};

// The flags each geometry takes besides the common ones.
const std::map<std::string_view, std::vector<std::string_view>>& geometry_flags() {
  static const std::vector<std::string_view> medium = {"--albedo",   "--g",       "--sigma-t",
                                                       "--material", "--channel", "--length-unit"};
  static const std::vector<std::string_view> run = {"--photons", "--batches", "--seed",
                                                    "--threads"};
  const auto join = [](std::initializer_list<std::vector<std::string_view>> parts) {
    std::vector<std::string_view> all;
    for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
  };
  static const std::vector<std::string_view> lit_object =
      join({medium, {"--eta"}, run, {"--split-orders"}});
  static const std::map<std::string_view, std::vector<std::string_view>> flags = {
      {"infinite", join({medium,
                         run,
                         {"--escape-radius", "--source", "--estimator", "--tallies",
                          "--split-orders", "--r-max", "--r-bins", "--z-min", "--z-max", "--z-bins",
                          "--theta-bins", "--phi-bins", "--fold-phi", "--rho-max", "--rho-bins"}})},
      {"half_space",
       join({medium,
             run,
             {"--escape-radius", "--eta", "--incidence", "--r-max", "--r-bins", "--z-max",
              "--z-bins", "--theta-bins", "--tallies", "--no-fluence", "--model-fluence"}})},
      {"sphere", lit_object},
      {"mesh", lit_object},
      {"slab", join({run, {"--escape-radius", "--split-orders"}})}};
  return flags;
}

// A flag given that the scene's geometry does not take is refused, naming both.
void refuse_other_flags(const CLI::App& command, const Scene& scene, const std::string& file) {
  const std::vector<std::string_view>& taken = geometry_flags().at(scene.geometry());
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0) continue;
    const std::string name = option->get_name();
    if (std::find(std::begin(kCommonFlags), std::end(kCommonFlags), name) !=
            std::end(kCommonFlags) ||
        std::find(taken.begin(), taken.end(), name) != taken.end()) {
      continue;
    }
    const std::string where =
        file.empty() ? "the built-in scene's geometry" : fmt::format("{}'s geometry.type", file);
    throw InputError(
        name,
        fmt::format("given, but {} is \"{}\", which does not take it", where, scene.geometry()),
        fmt::format("for the geometry \"{}\": {}, and the outputs, checkpoint, "
                    "--log-interval and --memory-limit flags",
                    scene.geometry(), fmt::join(taken, ", ")));
  }
}

// The infinite medium's tallies that --tallies names, and the request's switch for each.
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

// The half-space's --tallies: its one optional tally. The surface tallies (R_d(r), the exitant
// radiance and the totals) cost one bin lookup per exit and are always on.
void apply_tally_list(const std::string& list, HalfSpaceTallies& tallies) {
  if (list != "fluence" && list != "none") {
    throw InputError("--tallies", fmt::format("got \"{}\" for a half_space scene", list),
                     "fluence or none (R_d(r), the exitant radiance and the totals are always "
                     "tallied)");
  }
  tallies.fluence = list == "fluence";
}

// The flags at the built-in spec of the command's geometry, which --help shows.
SceneOptions default_options(std::string_view geometry) {
  const InfiniteMediumSpec infinite;
  const HalfSpaceSpec half_space;
  const bool searchlight = geometry == "half_space";
  const Medium& medium = searchlight ? half_space.medium : infinite.medium;
  SceneOptions o;
  o.out = searchlight ? "searchlight.h5" : "scatterlab.h5";
  o.source = to_string(infinite.source);
  o.estimator = to_string(infinite.tallies.estimator);
  o.tallies = searchlight ? (half_space.tallies.fluence ? "fluence" : "none")
                          : tally_list(infinite.tallies);
  o.albedo = medium.albedo;
  o.g = medium.g;
  o.sigma_t = medium.sigma_t;
  o.medium.length_unit = medium.length_unit;
  o.eta = half_space.eta;
  o.incidence = half_space.incidence_deg;
  o.run = run_options_of(searchlight ? half_space.run : infinite.run);
  o.r_max = searchlight ? half_space.grid.r.max : infinite.grid.r.max;
  o.r_bins = searchlight ? half_space.grid.r.bins : infinite.grid.r.bins;
  o.z_min = infinite.grid.z.min;
  o.z_max = searchlight ? half_space.grid.z.max : infinite.grid.z.max;
  o.z_bins = searchlight ? half_space.grid.z.bins : infinite.grid.z.bins;
  o.theta_bins = searchlight ? half_space.grid.theta_o.bins : infinite.grid.theta.bins;
  o.phi_bins = infinite.grid.phi.bins;
  o.rho_max = infinite.grid.rho.max;
  o.rho_bins = infinite.grid.rho.bins;
  return o;
}

// The given flags laid over one point of the scene, then its spec validated: each geometry takes
// the flags that mean something for it (refuse_other_flags refused the rest).
void apply_flags(const CLI::App& command, const SceneOptions& o, const Scene& scene,
                 SceneSpec& spec) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  // The medium's flags; a material brings its table's index unless the scene or --eta gives one.
  auto medium_flags = [&](Medium& medium, std::optional<MaterialOrigin>& material, double* eta) {
    const std::optional<double> material_eta = apply_medium_options(
        command, o.medium, o.albedo, o.g, o.sigma_t, scene.material, medium, material);
    if (eta == nullptr) return;
    if (material_eta && !scene.eta_given) *eta = *material_eta;
    if (given("--eta")) *eta = o.eta;
  };
  std::visit(
      Overloaded{
          [&](InfiniteMediumSpec& s) {
            medium_flags(s.medium, s.material, nullptr);
            if (given("--source")) {
              s.set_source(o.source == "point" ? SourceKind::point : SourceKind::pencil_beam);
            }
            if (given("--estimator")) {
              s.tallies.estimator =
                  o.estimator == "collision" ? Estimator::collision : Estimator::track_length;
            }
            if (given("--tallies")) apply_tally_list(o.tallies, s.tallies);
            if (given("--split-orders")) s.tallies.split_by_order = o.split_orders;
            apply_run_options(command, o.run, s.run);
            Grid& grid = s.grid;
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
            s.validate();
          },
          [&](HalfSpaceSpec& s) {
            medium_flags(s.medium, s.material, &s.eta);
            if (given("--incidence")) s.incidence_deg = o.incidence;
            apply_run_options(command, o.run, s.run);
            if (given("--r-max")) s.grid.r.max = o.r_max;
            if (given("--r-bins")) s.grid.r.bins = o.r_bins;
            if (given("--z-max")) s.grid.z.max = o.z_max;
            if (given("--z-bins")) s.grid.z.bins = o.z_bins;
            if (given("--theta-bins")) s.grid.theta_o.bins = o.theta_bins;
            if (given("--tallies")) apply_tally_list(o.tallies, s.tallies);
            if (given("--no-fluence")) s.tallies.fluence = false;
            s.validate();
            // The models' phi(r, z) goes beside the Monte Carlo's: without it there is nothing
            // to model.
            if (o.model_fluence && !s.tallies.fluence) {
              throw InputError("--model-fluence",
                               given("--no-fluence") || given("--tallies")
                                   ? "given without the fluence tally (--tallies none, "
                                     "--no-fluence)"
                                   : "given with the scene's tallies.fluence = false",
                               "--model-fluence with the fluence tally on (--tallies fluence)");
            }
          },
          [&](LitObjectSpec& s) {
            medium_flags(s.medium, s.material, &s.eta);
            if (given("--split-orders")) s.split_by_order = o.split_orders;
            apply_run_options(command, o.run, s.run);
            s.validate();
          },
          [&](LayeredSlabSpec& s) {
            if (given("--split-orders")) s.split_by_order = o.split_orders;
            apply_run_options(command, o.run, s.run);
            s.validate();
          }},
      spec);
}

// A mesh scene's object, read as render reads its [mesh] table, and checked as a lit object
// (closed, not passing through itself, clear of its light); without the renderer's libraries
// (Embree, tinyobjloader) there is no mesh to run.
void build_mesh(const Scene& scene, const std::string& file, LitObjectSpec& spec) {
#ifdef SCATTERLAB_WITH_RENDER
  const std::filesystem::path path(file);
  SceneMesh mesh = parse_scene_mesh(*scene.mesh_text, file, path.parent_path());
  spec.mesh_source = std::move(mesh.source);
  spec.mesh = std::make_shared<const TriangleMesh>(std::move(mesh.mesh));
#else
  (void)scene;
  (void)spec;
  throw InputError(
      "geometry.type",
      fmt::format("is \"mesh\" in {}, but this build of scatterlab has no renderer", file),
      "a build with Embree, tinyobjloader, OpenEXR and libpng: install them, then "
      "configure and build again");
#endif
}

std::string_view default_output(std::string_view geometry) {
  if (geometry == "half_space") return "searchlight.h5";
  if (geometry == "sphere" || geometry == "mesh") return "lit-sphere.h5";
  if (geometry == "slab") return "slab.h5";
  return "scatterlab.h5";
}

// A run to do: what, and where its file goes.
struct PlannedRun {
  SceneSpec spec;
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
RunPlan plan_runs(const CLI::App& command, const SceneOptions& o, std::string_view command_name,
                  std::string_view default_geometry, const LongRunOptions& long_run) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  // Each point of the file read strictly (keys, types), the flags over it, then the whole
  // validated (apply_flags).
  std::vector<SweepPoint> points =
      given("--scene")
          ? load_sweep(o.scene, Validation::by_caller, default_geometry)
          : parse_sweep("", "the built-in scene", Validation::by_caller, default_geometry);
  const std::string file = given("--scene") ? o.scene : "";
  // searchlight is simulate for the half-space: another geometry runs with simulate.
  if (default_geometry == "half_space" && points.front().scene.geometry() != "half_space") {
    throw InputError("geometry.type",
                     fmt::format("is \"{}\" in {}", points.front().scene.geometry(), file),
                     fmt::format("\"half_space\" for scatterlab {} (scatterlab simulate runs "
                                 "every geometry)",
                                 command_name));
  }
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
    Scene& scene = point.scene;
    refuse_other_flags(command, scene, file);
    if (scene.mesh_text) build_mesh(scene, file, std::get<LitObjectSpec>(scene.spec));
    apply_flags(command, o, scene, scene.spec);
#ifdef SCATTERLAB_WITH_RENDER
    if (scene.mesh_text) check_lit_mesh(std::get<LitObjectSpec>(scene.spec));
#endif
    const std::string fallback(default_output(scene.geometry()));
    std::filesystem::path output;
    std::string field = "--out";
    if (!out_dir.empty()) {
      field = dir_field;
      const std::string name =
          point.label.empty()
              ? std::filesystem::path(scene.output_path.value_or(fallback)).filename().string()
              : point.label + ".h5";
      output = std::filesystem::path(out_dir) / name;
    } else {
      output = given("--out") ? o.out : scene.output_path.value_or(fallback);
      if (!given("--out") && scene.output_path) field = "output.path";
    }
    plan.runs.push_back({std::move(scene.spec), output, field});
  }
  return plan;
}

void print_medium(const std::optional<MaterialOrigin>& material, const Medium& medium) {
  if (!material) return;
  fmt::print("  material {} ({}), {} channel: sigma_t {:.6g} / {}, lengths in {}\n", material->name,
             material->library, material->channel, medium.sigma_t, medium.length_unit,
             medium.length_unit);
}

std::string shape_text(const TallyResult& t) {
  std::string text;
  for (std::size_t i = 0; i < t.shape.size(); ++i) {
    text += (i ? " x " : "") + std::to_string(t.shape[i]);
  }
  return text;
}

void print_summary(const std::string& command, const InfiniteMediumSpec& spec,
                   const TransportOutput& out, const std::vector<ModelResult>&,
                   const std::string& path) {
  fmt::print("scatterlab {}: {} source, albedo {}, g {}, {} estimator\n", command,
             to_string(spec.source), spec.medium.albedo, spec.medium.g,
             to_string(spec.tallies.estimator));
  print_medium(spec.material, spec.medium);
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

void print_summary(const std::string& command, const HalfSpaceSpec& spec,
                   const TransportOutput& out, const std::vector<ModelResult>& models,
                   const std::string& path) {
  fmt::print("scatterlab {}: half-space, albedo {}, g {}, eta {}, incidence {} deg\n", command,
             spec.medium.albedo, spec.medium.g, spec.eta, spec.incidence_deg);
  print_medium(spec.material, spec.medium);
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

void print_summary(const std::string& command, const LitObjectSpec& spec,
                   const TransportOutput& out, const std::vector<ModelResult>&,
                   const std::string& path) {
  const std::string object =
      spec.mesh ? fmt::format("mesh ({}, in {})", spec.mesh_source, spec.medium.length_unit)
                : fmt::format("sphere of radius {} {}", spec.radius, spec.medium.length_unit);
  fmt::print("scatterlab {}: {}, {} light, albedo {}, g {}, eta {}\n", command, object,
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

void print_summary(const std::string& command, const LayeredSlabSpec& spec,
                   const TransportOutput& out, const std::vector<ModelResult>&,
                   const std::string& path) {
  fmt::print("scatterlab {}: slab of {} layers ({}), n above {}, below {}, {} weighting\n", command,
             spec.layers.size(), spec.length_unit, spec.n_above, spec.n_below,
             to_string(spec.weighting));
  print_run_time(out);
  print_energy_balance(out, slab_energy_tallies);
  print_figures_of_merit(out, {"diffuse_reflectance", "total_transmittance", "absorbed"});
  fmt::print("  wrote {}: R_d and T_t by r and angle, A by layer, depth and (r, z)\n", path);
}

// One spec on the transport engine (io/scene.hpp); a mesh in its own module, traced with Embree.
TransportOutput run_any_spec(const SceneSpec& spec, const ProgressCallback& progress,
                             const RunControl& control) {
#ifdef SCATTERLAB_WITH_RENDER
  if (const auto* object = std::get_if<LitObjectSpec>(&spec); object != nullptr && object->mesh) {
    return run_lit_mesh(*object, progress, control);
  }
#endif
  return run_spec(spec, progress, control);
}

int run_one(PlannedRun run, const std::string& command, const SceneOptions& o,
            const LongRunOptions& options, double log_interval, const std::string& command_line,
            World& world) {
  const std::uint64_t batches = run_settings(run.spec).batches;
  return run_with_checkpoints(
      command, options, run.output, fingerprint(run.spec), batches, log_interval, world,
      [&run](const ProgressCallback& progress, const RunControl& control) {
        return run_any_spec(run.spec, progress, control);
      },
      [&](const std::filesystem::path& path, const TransportOutput& out) {
        const std::vector<ModelResult> models =
            write_run_result(path, run.spec, out, command_line, o.model_fluence);
        std::visit([&](const auto& s) { print_summary(command, s, out, models, path.string()); },
                   run.spec);
      });
}

// A run that may take long says so before it starts. The time is at a cost per event typical of
// the lane walk on one core (the README's benchmarks: 8-25 ns; the one-photon walk's 30-130).
constexpr double typical_ns_per_event = 20.0;
constexpr double long_run_seconds = 600.0;

void warn_if_long(const std::string& command, const std::filesystem::path& output,
                  const TransportProblem& problem, int ranks) {
  const double per_photon = events_per_photon_bound(problem);
  const double events = per_photon * static_cast<double>(problem.run.photons);
  const int threads = batch_threads(problem.run) * ranks;
  const double seconds = events * typical_ns_per_event * 1e-9 / threads;
  if (!std::isfinite(seconds) || seconds < long_run_seconds) return;
  const std::string albedo = fmt::format(
      "{}albedo {}", problem.geometry == GeometryKind::slab ? "the layers' highest " : "",
      highest_albedo(problem));
  fmt::print(stderr,
             "{}: {} may take long: up to {:.3g} events a photon ({}), {:.3g} in all, "
             "about {} at {:g} ns an event on {} thread{}; fewer photons, a lower albedo or a "
             "smaller run.escape_radius shorten it\n",
             command, output.string(), per_photon, albedo, events, duration_text(seconds),
             typical_ns_per_event, threads, threads == 1 ? "" : "s");
}

int run_scene_command(const CLI::App& command, const SceneOptions& o, const std::string& name,
                      std::string_view default_geometry, const LongRunOptions& long_run,
                      double log_interval, const std::string& command_line, World& world) {
  const RunPlan run_plan = plan_runs(command, o, name, default_geometry, long_run);
  const std::vector<PlannedRun>& runs = run_plan.runs;
  const std::string& directory = run_plan.directory;
  // Every run's memory before any starts (engine.hpp): a sweep is refused whole, not halfway.
  std::vector<TransportProblem> problems;
  for (const PlannedRun& run : runs) {
    problems.push_back(transport_problem(run.spec));
    check_transport_memory(problems.back(), world.size(), long_run.resume);
  }
  // Then, with every run admitted, those that may take long say so.
  if (world.is_root()) {
    for (std::size_t i = 0; i < runs.size(); ++i) {
      warn_if_long(name, runs[i].output, problems[i], world.size());
    }
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
    const bool skip = !directory.empty() &&
                      world.communicator().broadcast_from_root(
                          complete_file_of(run.output, fingerprint(run.spec)) ? 1 : 0) != 0;
    if (skip) {
      if (world.is_root())
        fmt::print("skip {}: done already, same parameters\n", run.output.string());
      continue;
    }
    const int status = run_one(run, name, o, long_run, log_interval, command_line, world);
    if (status != 0) return status;
  }
  return 0;
}

// --help's list of the scene's keys, each geometry's, from the one table of them.
std::string scene_keys_footer() {
  std::string text = "Scene keys by geometry.type (scatterlab scene --keys: their meanings):";
  for (const std::string_view geometry : scene_geometries) {
    std::vector<std::string_view> keys;
    for (const SceneKey& key : scene_keys()) {
      if (scene_key_of(key, geometry)) keys.push_back(key.path);
    }
    text += fmt::format("\n  {}: {}", geometry, fmt::join(keys, ", "));
  }
  return text;
}

// simulate and searchlight: the same flags and the same path; `default_geometry` is the geometry
// without a scene file, or of a file that names none.
Action add_run_command(CLI::App& app, const std::string& name, const std::string& description,
                       std::string_view default_geometry, const std::string& example,
                       const std::string& command_line, World& world) {
  auto* command = app.add_subcommand(name, description);
  command->footer(scene_keys_footer());
  auto o = std::make_shared<SceneOptions>(default_options(default_geometry));
  // As in most Unix tools, a repeated flag takes its last value (scripts append overrides).
  command->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  CLI::Option* out = command->add_option(
      "-o,--out", o->out,
      "Output HDF5 file (default: the scene's output.path, else scatterlab.h5, searchlight.h5, "
      "lit-sphere.h5 or slab.h5 by geometry); for a sweep (a scene whose keys hold lists of "
      "values), the directory for its files, one per combination named from its values, at "
      "most 1000; done combinations are skipped; the directory is new, empty or one scatterlab "
      "wrote, and made when missing");
  command
      ->add_option("--out-dir", o->out_dir,
                   "Directory for the output file (named from the scene's output.path), or a "
                   "sweep's directory as --out; not with --out")
      ->excludes(out);
  command->add_option("--source", o->source, "infinite: beam (along +z) or point (isotropic)")
      ->check(CLI::IsMember({"beam", "point"}));
  command->add_option("--albedo", o->albedo, "Single-scattering albedo in [0, 1]");
  command->add_option("--g", o->g, "Henyey-Greenstein mean cosine, |g| < 1");
  command->add_option("--sigma-t", o->sigma_t, "Extinction coefficient in 1/length-unit");
  add_medium_options(*command, o->medium);
  command->add_option("--eta", o->eta,
                      "half_space, sphere, mesh: relative index n_medium / n_outside, in "
                      "[0.1, 10]; 1 for no interface; with a material, its table's value unless "
                      "given");
  command->add_option("--incidence", o->incidence,
                      "half_space: beam angle from the surface normal, degrees in [0, 90)");
  command->add_option("--estimator", o->estimator, "infinite: estimator of the volume tallies")
      ->check(CLI::IsMember({"collision", "track_length"}));
  CLI::Option* tallies = command->add_option(
      "--tallies", o->tallies,
      "infinite: comma-separated radiance, fluence, flux, fluence_spherical; half_space: fluence "
      "or none (the fluence phi(r, z) costs a bin lookup at every event; R_d(r), the exitant "
      "radiance and the totals are always tallied)");
  // A flag takes a value too (--split-orders=false), to switch off what a scene switches on.
  command->add_flag("--split-orders", o->split_orders,
                    "infinite, sphere, mesh, slab: also tally unscattered, once- and "
                    "multiply-scattered light apart");
  add_run_options(*command, o->run);
  command->add_option("--r-max", o->r_max, "Radial grid extent, in the length unit");
  command->add_option("--r-bins", o->r_bins, "Radial bins");
  command->add_option("--z-min", o->z_min, "infinite: axial grid start, in the length unit");
  command->add_option("--z-max", o->z_max, "Axial (depth) grid end, in the length unit");
  command->add_option("--z-bins", o->z_bins, "Axial (depth) bins");
  command->add_option("--theta-bins", o->theta_bins,
                      "Polar-angle bins: over [0, pi] in the infinite medium, exit angles over "
                      "[0, pi/2] for the half-space");
  command->add_option("--phi-bins", o->phi_bins,
                      "infinite: azimuth bins over [0, 2 pi], even; over [0, pi] with --fold-phi");
  command->add_flag("--fold-phi", o->fold_phi,
                    "infinite: fold phi onto [0, pi] (L is even in phi)");
  command->add_option("--rho-max", o->rho_max,
                      "infinite: spherical-shell grid extent, in the length unit");
  command->add_option("--rho-bins", o->rho_bins, "infinite: spherical shells (point source)");
  command->add_flag("--model-fluence", o->model_fluence,
                    "half_space: also write each diffusion model's phi(r, z) under /models "
                    "(about 1 ms per cell and model: a minute on the default grid); needs the "
                    "fluence tally");
  command->add_flag("--no-fluence", o->no_fluence, "half_space: same as --tallies none")
      ->excludes(tallies);
  const auto long_run = add_long_run_options(*command);
  add_memory_limit_option(*command);
  const auto log_interval = add_log_interval_option(*command);
  // Last, so that a bad value of a flag is reported before the positional file it spilled into.
  add_scene_option(*command, o->scene, example);
  return [command, o, name, default_geometry, long_run, log_interval, command_line, &world] {
    return run_scene_command(*command, *o, name, default_geometry, *long_run, *log_interval,
                             command_line, world);
  };
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
  return add_run_command(
      app, "simulate",
      "Run a scene of any geometry (its geometry.type): a pencil beam or isotropic point source "
      "in an infinite medium (the default: the paper's case, g = 0.9, albedo 0.5, Vavassori "
      "§4.1), binned radiance L(r,z,theta,phi), fluence and vector irradiance; a half-space "
      "behind a refractive boundary (data/scenes/searchlight.toml); a lit sphere or mesh "
      "(data/scenes/lit-sphere.toml), exitance against the angle from the lit pole or per "
      "triangle; or a layered slab as MCML runs it (data/scenes/skin-slab.toml). Every tally "
      "with its standard error, to HDF5. A flag that the scene's geometry does not take is "
      "refused by name.",
      "infinite", "data/scenes/paper-beam.toml", command_line, world);
}

Action add_searchlight_command(CLI::App& app, const std::string& command_line, World& world) {
  return add_run_command(
      app, "searchlight",
      "simulate for the half-space, its default geometry: a pencil beam on a semi-infinite "
      "medium z > 0 behind a smooth interface of relative index eta (Bitterli 2013, §2.3): "
      "diffuse reflectance R_d(r), exitant radiance L(r, theta_o), fluence phi(r, z) and the "
      "totals, each split by scattering order, with standard errors, and the diffusion models "
      "beside them, to HDF5. Without flags: albedo 0.99, g 0, eta 1.3, normal incidence.",
      "half_space", "data/scenes/searchlight.toml", command_line, world);
}

Action add_scene_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "scene",
      "The keys of scene files, from the program's one table of them: --schema writes a JSON "
      "Schema (for an editor that checks TOML as it is typed), --keys the key reference "
      "(docs/scene-keys.md)");
  auto schema = std::make_shared<bool>(false);
  auto keys = std::make_shared<bool>(false);
  CLI::Option* schema_flag =
      command->add_flag("--schema", *schema, "Write the JSON Schema of scene files to stdout");
  command->add_flag("--keys", *keys, "Write the key reference (Markdown) to stdout")
      ->excludes(schema_flag);
  return [schema, keys] {
    if (!*schema && !*keys) {
      throw InputError("scene", "neither --schema nor --keys given", "--schema or --keys");
    }
    fmt::print("{}", *schema ? scene_json_schema() : scene_key_reference());
    return 0;
  };
}

}  // namespace scatterlab::cli
