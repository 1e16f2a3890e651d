// Photon beam diffusion (models/photon_beam_diffusion.hpp) against independent evaluations:
// pbrt-v3's estimator of the same integrals (BeamDiffusionMS / BeamDiffusionSS: the dipole
// written out from its formulas, summed at exponential quantiles of the depth), written again
// here; the exact once-scattered exitance of the refractive single-scatter solution; and its own
// point values integrated over annuli and the whole surface.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/medium.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"
#include "scatterlab/models/photon_beam_diffusion.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"

namespace scatterlab {
namespace {

double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

// pbrt-v3's BeamDiffusionMS: depths at the midpoints of n exponential quantiles of
// sigma_t' exp(-sigma_t' t), each a unit dipole weighted by kappa rho'^2, averaged. The dipole is
// spelled out here from Bitterli eqs. 2.33 and 2.37, not taken from models/dipole.hpp.
double quantile_estimate(const HalfSpaceMedium& m, double r, int n) {
  const double s = m.reduced_sigma_t(), rho = m.reduced_albedo();
  const double diffusion = (2.0 * m.sigma_a + m.reduced_sigma_s()) / (3.0 * s * s);
  const double sigma_tr = std::sqrt(m.sigma_a / diffusion);
  const double c1 = fresnel_moment1(m.eta), c2 = fresnel_moment2(m.eta);
  const double ze = -2.0 * diffusion * (1.0 + 3.0 * c2) / (1.0 - 2.0 * c1);
  const double c_phi = 0.25 * (1.0 - 2.0 * c1), c_e = 0.5 * (1.0 - 3.0 * c2);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double zr = -std::log(1.0 - (i + 0.5) / n) / s;
    const double zv = -zr + 2.0 * ze;
    const double dr = std::hypot(r, zr), dv = std::hypot(r, zv);
    const double phi =
        inv_four_pi / diffusion * (std::exp(-sigma_tr * dr) / dr - std::exp(-sigma_tr * dv) / dv);
    const double flux =
        inv_four_pi * (zr * (1.0 + sigma_tr * dr) * std::exp(-sigma_tr * dr) / (dr * dr * dr) -
                       zv * (1.0 + sigma_tr * dv) * std::exp(-sigma_tr * dv) / (dv * dv * dv));
    const double kappa = 1.0 - std::exp(-2.0 * s * (dr + zr));
    sum += kappa * rho * rho * (c_phi * phi + c_e * flux);
  }
  return sum / n;
}

struct Case {
  double albedo, g, eta;
};
const Case cases[] = {{0.5, 0.0, 1.0},   {0.9, 0.0, 1.3},  {0.99, 0.8, 1.4},
                      {0.999, 0.0, 1.5}, {0.7, -0.3, 0.8}, {0.95, 0.9, 2.5}};
const double radii[] = {0.01, 0.1, 0.5, 1.0, 3.0, 10.0};

TEST(PhotonBeamDiffusion, MatchesPbrtsQuantileEstimatorAsItsSamplesGrow) {
  // The midpoint rule over quantiles converges as 1 / n^2: measured, its largest relative
  // distance from our quadrature over these cases is 2.0e-5 with 10^4 quantiles and 2.1e-8 with
  // 10^6. Held here: 10^5 within 1e-6. pbrt's own 100 quantiles are 3.4 % off at r = 0.01 (g 0.8,
  // where the integrand peaks within the first quantile) and at most 0.42 % from r = 0.1 on:
  // that is the error a renderer using pbrt's table carries, held to 4 % and 0.5 %.
  for (const Case& c : cases) {
    const HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(c.albedo, c.g, c.eta);
    const PhotonBeamDiffusion model = photon_beam_diffusion(medium);
    for (const double r : radii) {
      const double ours = photon_beam_diffusion_reflectance(model, r);
      SCOPED_TRACE(testing::Message()
                   << "albedo " << c.albedo << " g " << c.g << " eta " << c.eta << " r " << r);
      EXPECT_LT(relative_error(quantile_estimate(medium, r, 100000), ours), 1e-6);
      EXPECT_LT(relative_error(quantile_estimate(medium, r, 100), ours), r < 0.1 ? 0.04 : 0.005);
    }
  }
}

TEST(PhotonBeamDiffusion, OnceScatteredTermIsTheExactOnceScatteredExitance) {
  // The refractive single-scatter solution integrates over depth from 0 with the exit Fresnel
  // term (zero under total internal reflection) and carries the entry transmittance; ours starts
  // at t_c and is per unit power entering. Both quadratures are held to 1e-10.
  for (const Case& c : cases) {
    const HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(c.albedo, c.g, c.eta);
    const PhotonBeamDiffusion model = photon_beam_diffusion(medium);
    const Medium real = Medium::from_coefficients(medium.sigma_a, medium.sigma_s, medium.g, "mfp");
    const double entry = fresnel_dielectric_transmittance(1.0, c.eta);
    for (const double r : {0.01, 0.1, 0.5, 1.0, 3.0}) {
      const QuadratureResult exact = half_space_single_scatter_exitance(real, c.eta, r);
      EXPECT_LT(relative_error(entry * photon_beam_diffusion_single(model, r), exact.value), 1e-8)
          << "albedo " << c.albedo << " eta " << c.eta << " r " << r;
    }
  }
}

TEST(PhotonBeamDiffusion, AnnulusAveragesAndTotalAreItsPointValuesIntegrated) {
  // Annulus integrals and the total subtract kappa's share from the dipole's closed forms; the
  // point values integrate kappa directly. Two routes to one number, to 1e-7.
  for (const Case& c : cases) {
    const HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(c.albedo, c.g, c.eta);
    const PhotonBeamDiffusion model = photon_beam_diffusion(medium);
    const auto ring = [&](double r) {
      return 2.0 * pi * r * photon_beam_diffusion_reflectance(model, r);
    };
    QuadratureOptions options;
    options.rel_tol = 1e-9;
    const std::vector<double> edges{0.0, 0.05, 0.3, 1.0, 4.0};
    const std::vector<double> averages = photon_beam_diffusion_annulus_average(model, edges);
    for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
      const double integral = integrate_adaptive(ring, edges[i], edges[i + 1], options).value;
      const double area = pi * (edges[i + 1] * edges[i + 1] - edges[i] * edges[i]);
      EXPECT_LT(relative_error(averages[i], integral / area), 1e-7) << "albedo " << c.albedo;
    }
    // The whole surface: r = u / (1 - u) maps [0, 1) onto [0, inf).
    const auto whole = [&](double u) {
      if (u >= 1.0) return 0.0;
      const double r = u / (1.0 - u);
      return ring(r) / ((1.0 - u) * (1.0 - u));
    };
    const double total = integrate_adaptive(whole, 0.0, 1.0, options).value;
    EXPECT_LT(relative_error(photon_beam_diffusion_total_reflectance(model), total), 1e-7)
        << "albedo " << c.albedo;
  }
}

TEST(PhotonBeamDiffusion, KappaOnlyRemovesLight) {
  // Without kappa every source is the better dipole's; kappa in [0, 1] can only take from it,
  // the more the nearer the entry point, and nothing far from it.
  const HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(0.9, 0.0, 1.3);
  const PhotonBeamDiffusion model = photon_beam_diffusion(medium);
  QuadratureOptions options;
  options.rel_tol = 1e-10;
  double last_ratio = 0.0;
  for (const double r : {0.01, 0.1, 1.0, 20.0}) {
    const auto no_kappa = [&](double t) {
      return medium.reduced_albedo() * std::exp(-t) *
             dipole_reflectance(photon_beam_diffusion_source(model, t), r);
    };
    const double without = integrate_adaptive(no_kappa, 0.0, 60.0, options).value;
    const double with = photon_beam_diffusion_reflectance(model, r);
    EXPECT_LE(with, without * (1.0 + 1e-9)) << r;  // two quadratures, each to 1e-10
    EXPECT_GT(with / without, last_ratio) << r;    // it keeps 13 %, 51 %, 95 %, all
    last_ratio = with / without;
    if (r == 20.0) {
      EXPECT_LT(relative_error(with, without), 1e-9);
    }
  }
}

TEST(PhotonBeamDiffusion, NoScatteringGivesNoLightAndBadInputIsNamed) {
  const PhotonBeamDiffusion dark =
      photon_beam_diffusion(HalfSpaceMedium::from_albedo(0.0, 0.0, 1.3));
  EXPECT_EQ(photon_beam_diffusion_reflectance(dark, 1.0), 0.0);
  EXPECT_EQ(photon_beam_diffusion_single(dark, 1.0), 0.0);
  EXPECT_EQ(photon_beam_diffusion_total_reflectance(dark), 0.0);
  const PhotonBeamDiffusion model =
      photon_beam_diffusion(HalfSpaceMedium::from_albedo(0.9, 0.0, 1.3));
  EXPECT_TRUE(std::isinf(photon_beam_diffusion_single(model, 0.0)));
  EXPECT_THROW(photon_beam_diffusion_reflectance(model, -1.0), InputError);
  EXPECT_THROW(photon_beam_diffusion_single(model, std::numeric_limits<double>::quiet_NaN()),
               InputError);
  const std::vector<double> bad{0.0, 1.0, 1.0};
  EXPECT_THROW(photon_beam_diffusion_annulus_average(model, bad), InputError);
  EXPECT_THROW(photon_beam_diffusion(HalfSpaceMedium::from_albedo(0.9, 0.0, 3.0)), InputError);
}

}  // namespace
}  // namespace scatterlab
