#include "scatterlab/validate/lit_sphere_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"
#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/searchlight.hpp"

namespace scatterlab {
namespace {

constexpr double degree = std::numbers::pi / 180.0;

MonteCarloCurve tally_curve(const std::vector<TallyResult>& tallies, const std::string& name) {
  const TallyResult* t = find_tally(tallies, name);
  if (t == nullptr) throw std::logic_error("run has no tally " + name);
  return {t->mean, t->stderr_of_mean};
}

// Region errors of a model curve against a Monte Carlo curve (psi_edges in radians).
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

LitSphereComparison compare_lit_sphere(const LitSphereCase& lit_case,
                                       const LitSphereSettings& settings,
                                       const ProgressCallback& progress) {
  LitObjectSpec spec;
  spec.medium = lit_case.medium;
  spec.radius = lit_case.radius;
  spec.eta = lit_case.eta;
  spec.light = ObjectLight::directional;
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
  result.all = tally_curve(out.tallies, "exitance");
  result.multiple = tally_curve(out.tallies, "exitance_multiple");

  // The half-space's own multiply-scattered R_d(r), out to the sphere's diameter, by the same
  // Monte Carlo: a BSSRDF built on it carries the BSSRDF's error alone.
  HalfSpaceSpec half;
  half.medium = lit_case.medium;
  half.eta = lit_case.eta;
  half.grid.r = UniformAxis{0.0, 2.0 * lit_case.radius, settings.profile_rings};
  half.tallies.fluence = false;
  half.run = spec.run;
  // Deep photons wander long in a half-space of low absorption (marble: ~50 times the sphere's
  // cost per photon), so the profile takes a tenth of the photons; its noise is carried into the
  // BSSRDF's error bars (lit_sphere_exitance.hpp).
  half.run.photons = std::max<std::uint64_t>(settings.photons / 10, 10'000);
  half.validate();
  const TransportOutput profile_run = run_half_space(half);
  result.transport_seconds += profile_run.wall_seconds;
  const double entered = 1.0 - scalar_estimate(profile_run.tallies, "specular_reflectance").mean;
  MonteCarloCurve measured = tally_curve(profile_run.tallies, "reflectance_multiple");
  for (double& v : measured.mean) v /= entered;  // per unit power entering, as every profile
  for (double& v : measured.stderr_of_mean) v /= entered;

  const auto start = std::chrono::steady_clock::now();
  const Medium& m = lit_case.medium;
  const HalfSpaceMedium half_space{m.sigma_a(), m.sigma_s(), m.g, lit_case.eta};
  std::vector<DiffusionProfile> profiles;
  for (const ProfileModel model : all_profile_models) profiles.emplace_back(model, half_space);
  profiles.emplace_back(RingProfile{half.grid.r.edges(), std::move(measured.mean),
                                    std::move(measured.stderr_of_mean)},
                        half_space);
  for (const DiffusionProfile& profile : profiles) {
    LitSphereModelCurve curve{profile.model(),
                              lit_sphere_exitance(profile, lit_case.radius, result.psi_edges,
                                                  settings.integration_samples, settings.seed)};
    set_region_errors(curve, result.multiple, result.psi_edges);
    result.models.push_back(std::move(curve));
  }
  result.integration_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scatterlab
