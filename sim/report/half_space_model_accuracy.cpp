// The half-space models against the searchlight Monte Carlo, like with like
// (validate/half_space_comparison.hpp): over albedo x g x eta, each model's total diffuse
// reflectance and its mean relative error near the entry point (rings with r <= 1 mfp) and far,
// against the Monte Carlo part it models.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "scatterlab/report/suites.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/validate/half_space_comparison.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

std::string part_name(ModelPart part) {
  const std::string suffix = tally_suffix(part);
  return suffix.empty() ? "all" : suffix.substr(1);
}

double median(std::vector<double> v) {
  std::erase_if(v, [](double x) { return !std::isfinite(x); });
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

Section half_space_model_accuracy(const Profile& profile) {
  Section section;
  section.id = "half_space_models";
  section.title = "Half-space: analytic models against Monte Carlo";
  section.reference =
      "The searchlight Monte Carlo at normal incidence, split by scattering order: the diffusion "
      "models (dipole, better dipole, quantized diffusion) against the light scattered at least "
      "twice, the exact single scatter against the once-scattered light, their sums and the "
      "Grosjean beam against all of it. R_d(r) on 100 rings to 10 mfp.";
  section.tolerance =
      "The models are approximations: their errors are findings, not checks. Checked: no model's "
      "total diffuse reflectance above 1 (the sums of a diffusion model and the exact single "
      "scatter are reported, not bounded: those models count escaping light as a diffusion "
      "source), energy balance of each Monte Carlo run to 1e-12, the exact once-scattered total "
      "within 5 Monte Carlo standard errors, and no NaN.";
  section.table.columns = {"albedo", "g", "eta", "model", "part", "R_dr", "monte_carlo_R_dr",
                           "monte_carlo_stderr", "error_near", "error_far"};
  const std::vector<double> albedos =
      profile.quick ? std::vector<double>{0.5, 0.99} : std::vector<double>{0.5, 0.9, 0.99, 0.999};
  const std::vector<double> gs =
      profile.quick ? std::vector<double>{0.0, 0.9} : std::vector<double>{0.0, 0.5, 0.9};
  const std::vector<double> etas =
      profile.quick ? std::vector<double>{1.0, 1.3} : std::vector<double>{1.0, 1.3, 1.5};
  std::map<std::string, std::vector<double>> near_errors, far_errors;
  int sums_above_one = 0, cells = 0;
  for (const double albedo : albedos) {
    for (const double g : gs) {
      for (const double eta : etas) {
        HalfSpaceSpec spec;
        spec.medium.albedo = albedo;
        spec.medium.g = g;
        spec.eta = eta;
        spec.grid.r = UniformAxis{0.0, 10.0, 100};
        spec.tallies.fluence = false;
        spec.run.photons = profile.quick ? 20'000 : 500'000;
        spec.run.batches = 32;
        spec.run.seed = profile.seed + static_cast<std::uint64_t>(cells++);
        spec.run.threads = profile.threads;
        const TransportOutput out = run_half_space(spec);
        section.non_finite_values += count_non_finite(out.tallies);
        const auto scalar = [&](const std::string& name) {
          const TallyResult& t = tally(out.tallies, name);
          return std::pair{t.mean[0], t.stderr_of_mean[0]};
        };
        const std::string cell = fmt::format("albedo {}, g {}, eta {}", albedo, g, eta);
        const double specular = scalar("specular_reflectance").first;
        const double energy =
            specular + scalar("diffuse_reflectance").first + scalar("absorbed").first - 1.0;
        section.checks.push_back(
            {fmt::format("{}: energy residual {:.2g} within 1e-12", cell, energy),
             std::abs(energy) <= 1e-12});
        std::map<ModelPart, MonteCarloCurve> mc;
        for (const ModelPart part : {ModelPart::all, ModelPart::single, ModelPart::multiple}) {
          const TallyResult& t = tally(out.tallies, "reflectance" + tally_suffix(part));
          const auto [total, total_stderr] = scalar("diffuse_reflectance" + tally_suffix(part));
          mc[part] = {t.mean, t.stderr_of_mean, total, total_stderr};
        }
        const std::vector<double> r = spec.grid.r.edges();
        const HalfSpaceComparison c = compare_half_space(
            HalfSpaceMedium::from_albedo(albedo, g, eta), 1.0 - specular, r, {}, mc);
        for (const ModelCurve& m : c.reflectance) {
          const MonteCarloCurve& reference = mc[m.part];
          const bool sum = m.model.ends_with("+single_scatter");
          if (m.model == "single_scatter") {
            const double z = (reference.total - m.total) / reference.total_stderr;
            section.checks.push_back(
                {fmt::format("{}: exact once-scattered {:.6f} against Monte Carlo {:.6f} (z {:.2f})",
                             cell, m.total, reference.total, z),
                 std::abs(z) <= 5.0});
          } else if (!sum) {
            section.checks.push_back(
                {fmt::format("{}: {} R_dr {:.6f} <= 1", cell, m.model, m.total), m.total <= 1.0});
          }
          if (sum && m.total > 1.0) ++sums_above_one;
          const std::string key = fmt::format("{} [{}]", m.model, part_name(m.part));
          near_errors[key].push_back(m.near_error);
          far_errors[key].push_back(m.far_error);
          section.non_finite_values += !std::isfinite(m.total);
          section.table.rows.push_back(
              {fmt::format("{}", albedo), fmt::format("{}", g), fmt::format("{}", eta), m.model,
               part_name(m.part), fmt::format("{:.6f}", m.total),
               fmt::format("{:.6f}", reference.total), fmt::format("{:.1e}", reference.total_stderr),
               fmt::format("{:.4f}", m.near_error), fmt::format("{:.4f}", m.far_error)});
        }
      }
    }
  }
  section.findings = fmt::format(
      "Median over {} cells of each model's mean relative error against the Monte Carlo part it "
      "models, near (r <= 1 mfp) and far:\n\n| model [part] | near | far |\n|---|---|---|\n",
      cells);
  for (const auto& [key, errors] : near_errors) {
    section.findings += fmt::format("| {} | {:.3f} | {:.3f} |\n", key, median(errors),
                                    median(far_errors[key]));
  }
  section.findings += fmt::format(
      "\nSums of a diffusion model and the exact single scatter above 1: {} of {}.\n",
      sums_above_one, 3 * cells);
  return section;
}

}  // namespace scatterlab::report
