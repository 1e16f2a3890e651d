// scatterlab validate deon: d'Eon & Irving 2011's point-source fluence comparison (Vavassori
// §4.1 Fig. 4.2, §4.4) — Monte Carlo, the exact solution, classical diffusion and Grosjean for
// albedos 0.01 to 0.99, g = 0 — as an error table on stdout, CSV tables and PNG plots.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include "commands.hpp"
#include "log_interval_option.hpp"
#include "memory_limit_option.hpp"
#include "prepare_outputs.hpp"
#include "progress_reporter.hpp"
#include "run_options.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/io/plot.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/validate/half_space_comparison.hpp"
#include "scatterlab/validate/lit_sphere_comparison.hpp"
#include "scatterlab/validate/point_source_comparison.hpp"
#include "scatterlab/validate/validation_report.hpp"

namespace scatterlab::cli {
namespace {

// The albedos of validate deon, each run with its own seed, --seed + i.
const std::vector<double> deon_albedos = {0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99};

struct ValidateOptions {
  std::string out = "validate-deon";
  double photons = 1e6;  // a double so that 1e6 reads as in scene files
  bool quick = false;
  int threads = 0;
  std::uint64_t seed = 1;
  double log_interval = 0.0;  // set from --log-interval (log_interval_option.hpp)
};

void print_written(const std::vector<std::filesystem::path>& files) {
  for (const std::filesystem::path& path : files) fmt::print("  wrote {}\n", path.string());
}

int run_deon(const ValidateOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  PointSourceComparisonSettings settings;
  settings.photons = options.quick ? 20'000 : photon_count(options.photons);
  settings.threads = options.threads;
  settings.seed = options.seed;
  const std::vector<double>& albedos = deon_albedos;
  std::vector<PointSourceComparison> comparisons;
  ProgressReporter reporter("validate deon", "albedos", options.log_interval);
  reporter.start(0, albedos.size());
  for (std::size_t i = 0; i < albedos.size(); ++i) {
    // A seed per albedo: with one seed the albedos share their first flights, and a fluctuation
    // in one shell repeats in every row of the table.
    PointSourceComparisonSettings per_albedo = settings;
    per_albedo.seed = settings.seed + i;
    comparisons.push_back(compare_point_source(albedos[i], per_albedo));
    reporter.update(i + 1, albedos.size());
  }
  reporter.finish();
  const auto files = write_point_source_report(comparisons, options.out);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print(
      "scatterlab validate deon: isotropic point source, g = 0, {} photons per albedo, "
      "shells of {} mfp to {} mfp\n",
      settings.photons, settings.rho.width(), settings.rho.max);
  fmt::print(
      "mean relative error of shell-averaged fluence against the exact solution, near "
      "(r < 1 mfp) / far (r >= 1 mfp):\n{}",
      point_source_error_table(comparisons));
  fmt::print("  {:.2f} s\n", seconds);
  print_written(files);
  return 0;
}

struct SearchlightValidateOptions {
  std::string out = "validate-searchlight";
  double photons = 1e7;
  double albedo = 0.99, g = 0.0, eta = 1.3;
  bool quick = false;
  int threads = 0;
  std::uint64_t seed = 1;
  double log_interval = 0.0;  // set from --log-interval (log_interval_option.hpp)
};

MonteCarloCurve curve(const std::vector<TallyResult>& tallies, const std::string& name,
                      const std::string& total_name = "") {
  const TallyResult* t = find_tally(tallies, name);
  if (t == nullptr) throw std::logic_error("searchlight run has no tally " + name);
  MonteCarloCurve c{t->mean, t->stderr_of_mean};
  if (!total_name.empty()) {
    const ScalarEstimate total = scalar_estimate(tallies, total_name);
    c.total = total.mean;
    c.total_stderr = total.stderr_of_mean;
  }
  return c;
}

// The half-space comparison, like with like (validate/half_space_comparison.hpp): the searchlight
// Monte Carlo's multiply-scattered part against the diffusion models, its once-scattered part
// against the exact refractive single-scatter solution, and its total against their sums and the
// Grosjean beam (R_d(r) and phi(r, z), Bitterli's pencil plots).
int run_searchlight_validation(const SearchlightValidateOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  HalfSpaceSpec spec;
  spec.medium.albedo = o.albedo;
  spec.medium.g = o.g;
  spec.eta = o.eta;
  spec.run.photons = o.quick ? 100'000 : photon_count(o.photons);
  // R_d(r) on 100 rings to 10 mfp; phi(r, z) on 100 x 20 cells to 10 mfp deep: the models'
  // cell averages are 2-D adaptive integrals (~1 ms each).
  // Batches as `scatterlab searchlight` (run_settings.hpp), so that the same photons and seed
  // give the same standard errors there and here.
  spec.grid.r.bins = 100;
  spec.grid.z.bins = 20;
  spec.run.threads = o.threads;
  spec.run.seed = o.seed;
  spec.validate();
  ProgressReporter reporter("validate searchlight", "batches", o.log_interval);
  reporter.start(0, spec.run.batches);
  const TransportOutput out =
      run_half_space(spec, [&reporter](const BatchProgress& done) { reporter.update(done); });
  reporter.finish();
  const MonteCarloCurve specular = curve(out.tallies, "specular_reflectance");
  const std::vector<double> r = spec.grid.r.edges(), z = spec.grid.z.edges();

  std::map<ModelPart, MonteCarloCurve> reflectance, fluence;
  for (const ModelPart part : {ModelPart::all, ModelPart::single, ModelPart::multiple}) {
    const std::string suffix = tally_suffix(part);
    reflectance[part] = curve(out.tallies, "reflectance" + suffix, "diffuse_reflectance" + suffix);
    if (part != ModelPart::single) fluence[part] = curve(out.tallies, "fluence" + suffix);
  }
  const HalfSpaceComparison comparison =
      compare_half_space(HalfSpaceMedium::from_albedo(o.albedo, o.g, o.eta), 1.0 - specular.mean[0],
                         r, z, reflectance, fluence);
  auto files = write_half_space_report(comparison, o.out, "searchlight");

  const ModelCurve& exact_curve = comparison.reflectance.front();  // single_scatter
  const SingleScatterReflectance exact{exact_curve.values, exact_curve.error, exact_curve.total,
                                       exact_curve.total_error};
  const MonteCarloCurve& single = reflectance[ModelPart::single];
  const SingleScatterAgreement agreement =
      compare_single_scatter(single, exact, single.total, single.total_stderr);
  const auto more =
      write_single_scatter_report(r, single, exact, comparison.medium, o.out, "searchlight");
  files.insert(files.end(), more.begin(), more.end());

  fmt::print("scatterlab validate searchlight: albedo {}, g {}, eta {}, {} photons\n", o.albedo,
             o.g, o.eta, spec.run.photons);
  fmt::print(
      "  each model against the Monte Carlo part it models (all = single + multiple); "
      "errors: mean |model - MC| / MC over resolved rings, near (r <= 1 mfp) and far\n");
  fmt::print("  {:<38} {:<8} {:>9} {:>21} {:>11} {:>11}\n", "model", "part", "R_dr",
             "Monte Carlo R_dr", "error near", "error far");
  for (const ModelCurve& m : comparison.reflectance) {
    const MonteCarloCurve& mc = reflectance[m.part];
    const std::string part = tally_suffix(m.part).empty() ? "all" : tally_suffix(m.part).substr(1);
    fmt::print("  {:<38} {:<8} {:>9.6f} {:>21} {:>10.2f}% {:>10.2f}%\n", m.model, part, m.total,
               estimate_text({mc.total, mc.total_stderr}), 100.0 * m.near_error,
               100.0 * m.far_error);
  }
  fmt::print(
      "  once scattered: exact total {:.6f}, Monte Carlo {} {}; {} rings, max |z| {:.2f}, mean "
      "z^2 {:.2f}\n",
      exact.total, estimate_text({single.total, single.total_stderr}),
      sigma_text({single.total, single.total_stderr}, exact.total), agreement.rings,
      agreement.max_abs_z, agreement.mean_squared_z);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("  {:.2f} s\n", seconds);
  print_written(files);
  return 0;
}

struct LitSphereValidateOptions {
  std::string out = "validate-litsphere";
  // At these defaults the two sides' standard errors are alike, ~1 % per psi bin on the lit side.
  double photons = 1e6;  // per case
  int samples = 4'000;   // per psi bin and model
  bool quick = false;
  int threads = 0;
  std::uint64_t seed = 1;
  double log_interval = 0.0;  // set from --log-interval (log_interval_option.hpp)
};

// The lit sphere, like with like (validate/lit_sphere_comparison.hpp): each diffusion BSSRDF
// integrated over the sphere against the path-traced sphere's multiply-scattered exitance.
int run_lit_sphere_validation(const LitSphereValidateOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  LitSphereSettings settings;
  settings.photons = o.quick ? 10'000 : photon_count(o.photons);
  settings.integration_samples = o.quick ? 500 : o.samples;
  settings.threads = o.threads;
  const std::vector<LitSphereCase> cases = lit_sphere_cases();
  std::vector<LitSphereComparison> comparisons;
  ProgressReporter reporter("validate litsphere", "cases", o.log_interval);
  reporter.start(0, cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    settings.seed = o.seed + i;  // a seed per case, as validate deon's per albedo
    comparisons.push_back(compare_lit_sphere(cases[i], settings));
    reporter.update(i + 1, cases.size());
  }
  reporter.finish();
  const auto files = write_lit_sphere_report(comparisons, o.out);
  fmt::print(
      "scatterlab validate litsphere: directional light, {} photons per case, {} samples per psi "
      "bin and model\n",
      settings.photons, settings.integration_samples);
  fmt::print(
      "  each diffusion BSSRDF (Bitterli eq. 2.16) integrated over the lit sphere against the path-"
      "traced exitance of light scattered at least twice; 'measured' is the same BSSRDF on the "
      "half-space Monte Carlo's own multiply-scattered R_d(r) (the BSSRDF's error alone); mean "
      "|model - MC| / MC over resolved psi bins: lit side (psi < 80 deg), terminator (80-100), "
      "shadow side (> 100)\n");
  fmt::print("{}", lit_sphere_error_table(comparisons));
  double transport = 0.0, integration = 0.0;
  for (const LitSphereComparison& c : comparisons) {
    transport += c.transport_seconds;
    integration += c.integration_seconds;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("  {:.2f} s ({:.2f} s path tracing, {:.2f} s BSSRDF integration)\n", seconds,
             transport, integration);
  print_written(files);
  return 0;
}

}  // namespace

Action add_validate_command(CLI::App& app) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* validate = app.add_subcommand(
      "validate", "Compare the analytic models and the exact solutions against Monte Carlo");
  validate->require_subcommand(1);
  CLI::App* deon = validate->add_subcommand(
      "deon",
      "Point-source fluence r^2 phi(r) for albedos 0.01-0.99: Monte Carlo, exact, diffusion, "
      "Grosjean (d'Eon & Irving 2011); error table, CSV and PNG plots");
  deon->add_option(
      "-o,--out", options->out,
      "Directory for the CSV and PNG files: new, empty or one scatterlab wrote (made if missing)");
  CLI::Option* deon_photons = deon->add_option("--photons", options->photons, "Photons per albedo");
  // --quick sets the photons: both would be a silent choice.
  deon->add_flag("--quick", options->quick, "2e4 photons per albedo, for tests; not with --photons")
      ->excludes(deon_photons);
  deon->add_option("--threads", options->threads, threads_help());
  add_memory_limit_option(*deon);
  const auto deon_log_interval = add_log_interval_option(*deon);
  deon->add_option("--seed", options->seed,
                   "Random seed of the first albedo (the next take the next seeds), in "
                   "[0, 2^63 - 7]");
  auto half_space = std::make_shared<SearchlightValidateOptions>();
  CLI::App* searchlight = validate->add_subcommand(
      "searchlight",
      "Half-space, like with like: the searchlight Monte Carlo's multiply-scattered part against "
      "the dipole, better dipole, quantized diffusion and photon beam diffusion, its "
      "once-scattered part against the exact refractive single-scatter solution, and its total "
      "against their sums and the Grosjean beam (R_d(r), phi(r, z); linear, log, sqrt and r R "
      "plots)");
  searchlight->add_option(
      "-o,--out", half_space->out,
      "Directory for the CSV and PNG files: new, empty or one scatterlab wrote (made if missing)");
  CLI::Option* searchlight_photons =
      searchlight->add_option("--photons", half_space->photons, "Photons");
  searchlight->add_option("--albedo", half_space->albedo, "Albedo");
  searchlight->add_option("--g", half_space->g, "Henyey-Greenstein g");
  searchlight->add_option("--eta", half_space->eta, "Relative index");
  searchlight->add_flag("--quick", half_space->quick, "1e5 photons, for tests; not with --photons")
      ->excludes(searchlight_photons);
  searchlight->add_option("--threads", half_space->threads, threads_help());
  add_memory_limit_option(*searchlight);
  const auto searchlight_log_interval = add_log_interval_option(*searchlight);
  searchlight->add_option("--seed", half_space->seed, "Random seed, in [0, 2^63 - 1]");
  auto sphere = std::make_shared<LitSphereValidateOptions>();
  CLI::App* litsphere = validate->add_subcommand(
      "litsphere",
      "Lit sphere, like with like: the dipole, better dipole and quantized diffusion BSSRDFs "
      "integrated over a sphere under a directional light against the path-traced sphere's "
      "multiply-scattered exitance M(psi), for Jensen et al. 2001's marble and skin1 (each "
      "channel) and three media in mfp, and the same BSSRDF on the half-space Monte Carlo's own "
      "profile; error table (lit side, terminator, shadow side), CSV and "
      "PNG plots");
  litsphere->add_option(
      "-o,--out", sphere->out,
      "Directory for the CSV and PNG files: new, empty or one scatterlab wrote (made if missing)");
  CLI::Option* litsphere_photons =
      litsphere->add_option("--photons", sphere->photons, "Photons per case");
  CLI::Option* litsphere_samples = litsphere->add_option(
      "--samples", sphere->samples, "BSSRDF integration samples per psi bin and model, >= 2");
  litsphere
      ->add_flag("--quick", sphere->quick,
                 "1e4 photons and 500 samples per case, for tests; not with --photons or --samples")
      ->excludes(litsphere_photons)
      ->excludes(litsphere_samples);
  litsphere->add_option("--threads", sphere->threads, threads_help());
  add_memory_limit_option(*litsphere);
  const auto litsphere_log_interval = add_log_interval_option(*litsphere);
  litsphere->add_option("--seed", sphere->seed,
                        "Random seed of the first case (the next take the next seeds), in "
                        "[0, 2^63 - 10]");
  return [options, deon, half_space, searchlight, sphere, litsphere, deon_log_interval,
          searchlight_log_interval, litsphere_log_interval] {
    options->log_interval = *deon_log_interval;
    half_space->log_interval = *searchlight_log_interval;
    sphere->log_interval = *litsphere_log_interval;
    std::string out;
    if (deon->parsed()) {
      check_threads(options->threads, "--threads");
      check_seed(options->seed, "--seed", deon_albedos.size());  // a seed per albedo
      out = options->out;
    } else if (searchlight->parsed()) {
      check_threads(half_space->threads, "--threads");
      check_seed(half_space->seed, "--seed");
      out = half_space->out;
    } else {
      check_threads(sphere->threads, "--threads");
      check_seed(sphere->seed, "--seed", lit_sphere_cases().size());  // a seed per case
      if (sphere->samples < 2)
        throw InputError("--samples", fmt::format("got {}", sphere->samples), "an integer >= 2");
      out = sphere->out;
    }
    OutputPlan plan;
    plan.output_directory("--out", out);
    prepare_outputs(plan);
    require_plotting();  // before the runs, not after them
    if (deon->parsed()) return run_deon(*options);
    if (searchlight->parsed()) return run_searchlight_validation(*half_space);
    if (litsphere->parsed()) return run_lit_sphere_validation(*sphere);
    return 1;
  };
}

}  // namespace scatterlab::cli
