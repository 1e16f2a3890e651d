// The analytic models that approximate a continuum, against that continuum to their stated
// tolerance: quantized diffusion's sum of Gaussians (d'Eon & Irving 2011, §3) against the depth
// integral it discretises (models/quantized_diffusion.hpp, QuantizedDiffusionContinuum), on
// every ring out to the last one its accuracy is stated for, over albedo x g x eta, at several
// tolerances. Error against cost: the worst error at each tolerance, and the Gaussians it takes.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "scatterlab/models/quantized_diffusion.hpp"
#include "scatterlab/report/suites.hpp"

namespace scatterlab::report {
namespace {

double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// The worst relative error found so far, and where it lies.
struct Worst {
  double error = 0.0;
  std::string where;
};

}  // namespace

Section model_continua(const Profile& profile) {
  Section section;
  section.id = "model_continua";
  section.title = "Models against the continuum they approximate";
  section.reference =
      "Quantized diffusion's sum of Gaussians against the continuum it discretises: the depth "
      "integral, by adaptive quadrature to a relative 1e-10, of better-dipole point sources of "
      "strength alpha'^2 along the beam (QuantizedDiffusionContinuum). R_d averaged over rings "
      "0.1 / sigma_t' wide out to 10 / sigma_t', the last ring its accuracy is stated for, and "
      "the total R_dr.";
  section.tolerance =
      "The model's stated relative_tolerance eps, on every ring and the total "
      "(models/quantized_diffusion.hpp); no NaN or Inf.";
  section.table.columns = {"relative_tolerance", "media",      "gaussians_max",     "seconds",
                           "worst_ring_error",   "worst_ring", "worst_total_error", "worst_total"};
  const std::vector<double> tolerances =
      profile.quick ? std::vector<double>{1e-2, 1e-4} : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-6};
  const std::vector<double> albedos =
      profile.quick ? std::vector<double>{0.01, 0.5, 0.99, 1.0}
                    : std::vector<double>{0.01, 0.1, 0.5, 0.9, 0.99, 0.999, 1.0};
  const std::vector<double> gs{0.0, 0.9};
  const std::vector<double> etas{1.0, 1.5};
  // Every stride-th ring, and each of the last ten (the far field, where the sum is hardest).
  const std::size_t stride = profile.quick ? 30 : 10;

  LinePlot plot{
      "Quantized diffusion against its continuum:\nworst relative error over media and "
      "rings out to $10/\\sigma_t'$",
      "relative_tolerance asked, $\\epsilon$",
      "worst relative error",
      AxisScale::log,
      true,
      {}};
  std::vector<double> asked, ring_errors, total_errors;
  for (const double tolerance : tolerances) {
    Worst ring, total;
    std::size_t gaussians = 0, media = 0;
    double seconds = 0.0;
    for (const double albedo : albedos) {
      for (const double g : gs) {
        for (const double eta : etas) {
          const HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(albedo, g, eta);
          const std::string where = fmt::format("albedo {} g {} eta {}", albedo, g, eta);
          std::vector<double> edges;
          for (int i = 0; i <= 100; ++i) edges.push_back(0.1 * i / medium.reduced_sigma_t());
          const auto start = std::chrono::steady_clock::now();
          const QuantizedDiffusion model = quantized_diffusion(medium, tolerance);
          const std::vector<double> average =
              quantized_diffusion_reflectance_annulus_average(model, edges);
          const double model_total = quantized_diffusion_total_reflectance(model);
          seconds +=
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          gaussians = std::max(gaussians, model.variance.size());
          ++media;
          const QuantizedDiffusionContinuum continuum(medium);
          for (std::size_t k = 0; k + 1 < edges.size(); k += (k < 90 ? stride : 1)) {
            const double error =
                relative_error(average[k], continuum.annulus_average(edges[k], edges[k + 1]));
            if (!std::isfinite(average[k])) ++section.non_finite_values;
            // Written so that a NaN error counts as the worst.
            if (!(error <= ring.error)) ring = {error, fmt::format("{} ring {}", where, k)};
          }
          const double error = relative_error(model_total, continuum.total());
          if (!std::isfinite(model_total)) ++section.non_finite_values;
          if (!(error <= total.error)) total = {error, where};
        }
      }
    }
    section.checks.push_back({fmt::format("eps {:g}: worst ring {:.3g} eps ({}) within eps",
                                          tolerance, ring.error / tolerance, ring.where),
                              ring.error <= tolerance});
    section.checks.push_back({fmt::format("eps {:g}: worst total {:.3g} eps ({}) within eps",
                                          tolerance, total.error / tolerance, total.where),
                              total.error <= tolerance});
    section.table.rows.push_back({fmt::format("{:g}", tolerance), fmt::format("{}", media),
                                  fmt::format("{}", gaussians), fmt::format("{:.3g}", seconds),
                                  fmt::format("{:.3g}", ring.error), ring.where,
                                  fmt::format("{:.3g}", total.error), total.where});
    asked.push_back(tolerance);
    ring_errors.push_back(ring.error);
    total_errors.push_back(total.error);
    section.findings += fmt::format(
        "- eps {:g}: worst ring {:.3g} eps ({}), worst total {:.3g} eps ({}); at most {} "
        "Gaussians, {:.3g} s for {} models and their rings.\n",
        tolerance, ring.error / tolerance, ring.where, total.error / tolerance, total.where,
        gaussians, seconds, media);
  }
  plot.series.push_back({"asked: error = $\\epsilon$", asked, asked, {}, false, "exact"});
  plot.series.push_back({"worst ring", asked, ring_errors, {}, true, "quantized_diffusion"});
  plot.series.push_back({"worst total $R_{dr}$", asked, total_errors, {}, true, {}});
  section.figures.push_back({section.id, plot});
  return section;
}

}  // namespace scatterlab::report
