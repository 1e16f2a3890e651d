#include "scatterlab/validate/lit_sphere_comparison.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/tally/tally_result.hpp"

namespace scatterlab {
namespace {

constexpr double degree = std::numbers::pi / 180.0;

MonteCarloCurve exitance_curve(const std::vector<TallyResult>& tallies, const std::string& name) {
  const TallyResult* t = find_tally(tallies, name);
  if (t == nullptr) throw std::logic_error("lit sphere run has no tally " + name);
  return {t->mean, t->stderr_of_mean};
}

}  // namespace

std::vector<LitSphereCase> lit_sphere_cases() {
  std::vector<LitSphereCase> cases;
  for (const char* material : {"marble", "skin1"}) {
    for (const char* channel : {"red", "green", "blue"}) {
      const ResolvedMaterial resolved = resolve_material(
          {material, channel, "mm", std::nullopt}, {"material", "channel", "length_unit", "g"});
      cases.push_back({fmt::format("{} {} (Jensen et al. 2001), R = 10 mm", material, channel),
                       fmt::format("{}_{}", material, channel), resolved.medium, 10.0,
                       resolved.eta});
    }
  }
  struct Abstract {
    double albedo, g, radius;
  };
  for (const Abstract& a :
       {Abstract{0.99, 0.0, 10.0}, Abstract{0.8, 0.0, 10.0}, Abstract{0.99, 0.75, 20.0}}) {
    cases.push_back({fmt::format("albedo {:g}, g {:g}, R = {:g} mfp", a.albedo, a.g, a.radius),
                     fmt::format("albedo_{:g}_g_{:g}_R_{:g}", a.albedo, a.g, a.radius),
                     Medium::from_albedo(a.albedo, 1.0, a.g, "mfp"), a.radius, 1.3});
  }
  return cases;
}

void set_region_errors(LitSphereModelCurve& curve, const MonteCarloCurve& monte_carlo,
                       const std::vector<double>& psi_edges) {
  double sum[3] = {0.0, 0.0, 0.0};
  int count[3] = {0, 0, 0};
  for (std::size_t b = 0; b + 1 < psi_edges.size(); ++b) {
    const double mc = monte_carlo.mean[b];
    if (!(mc > 3.0 * monte_carlo.stderr_of_mean[b])) continue;
    const double middle = 0.5 * (psi_edges[b] + psi_edges[b + 1]);
    const int region = middle < 80.0 * degree ? 0 : middle <= 100.0 * degree ? 1 : 2;
    sum[region] += std::abs(curve.exitance.mean[b] - mc) / mc;
    ++count[region];
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  curve.lit_error = count[0] > 0 ? sum[0] / count[0] : nan;
  curve.terminator_error = count[1] > 0 ? sum[1] / count[1] : nan;
  curve.shadow_error = count[2] > 0 ? sum[2] / count[2] : nan;
}

LitSphereComparison compare_lit_sphere(const LitSphereCase& lit_case,
                                       const LitSphereSettings& settings,
                                       const ProgressCallback& progress) {
  LitSphereSpec spec;
  spec.medium = lit_case.medium;
  spec.radius = lit_case.radius;
  spec.eta = lit_case.eta;
  spec.light = SphereLight::directional;
  spec.psi = UniformAxis{0.0, std::numbers::pi, settings.psi_bins};
  spec.split_by_order = true;
  spec.run.photons = settings.photons;
  spec.run.threads = settings.threads;
  spec.run.seed = settings.seed;
  spec.validate();

  LitSphereComparison result;
  result.lit_case = lit_case;
  result.psi_edges = spec.psi.edges();
  const TransportOutput out = run_lit_sphere(spec, progress);
  result.transport_seconds = out.wall_seconds;
  result.all = exitance_curve(out.tallies, "exitance");
  result.multiple = exitance_curve(out.tallies, "exitance_multiple");

  const auto start = std::chrono::steady_clock::now();
  const Medium& m = lit_case.medium;
  const HalfSpaceMedium half_space{m.sigma_a(), m.sigma_s(), m.g, lit_case.eta};
  for (const ProfileModel model : all_profile_models) {
    LitSphereModelCurve curve{
        model, lit_sphere_exitance(DiffusionProfile(model, half_space), lit_case.radius,
                                   result.psi_edges, settings.integration_samples, settings.seed)};
    set_region_errors(curve, result.multiple, result.psi_edges);
    result.models.push_back(std::move(curve));
  }
  result.integration_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scatterlab
