// The half-space diffusion models: boundary fits against a quadrature of the Fresnel formula,
// the dipoles against values computed by hand from Bitterli §2.5 / d'Eon 2012, closed-form
// totals and annulus averages against each other, the Grosjean beam against its parts, the
// exact single-scatter solver and its energy bound, and every model at the extremes (never NaN).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/boundary_reflection.hpp"
#include "scatterlab/models/dipole.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/medium.hpp"
#include "scatterlab/models/grosjean_beam.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"

namespace scatterlab {
namespace {

// Unpolarised Fresnel reflectance for light inside a medium of relative index eta meeting the
// surface at cosine mu (Born & Wolf §1.5.2), written out independently of the fits.
double fresnel_inside(double eta, double mu) {
  const double sin2_t = eta * eta * (1.0 - mu * mu);
  if (sin2_t >= 1.0) return 1.0;
  const double ct = std::sqrt(1.0 - sin2_t);
  const double rs = (eta * mu - ct) / (eta * mu + ct);
  const double rp = (mu - eta * ct) / (mu + eta * ct);
  return 0.5 * (rs * rs + rp * rp);
}

double fresnel_moment_quadrature(double eta, int n) {
  std::vector<double> breaks{0.0, 1.0};
  if (eta > 1.0) breaks = {0.0, std::sqrt(1.0 - 1.0 / (eta * eta)), 1.0};  // critical angle
  return integrate_adaptive([&](double mu) { return fresnel_inside(eta, mu) * std::pow(mu, n); },
                            breaks)
      .value;
}

TEST(BoundaryReflection, FitsMatchTheFresnelQuadrature) {
  for (const double eta : {0.5, 0.75, 0.9, 1.0001, 1.1, 1.33, 1.5, 2.0, 2.5}) {
    EXPECT_NEAR(2.0 * fresnel_moment1(eta), 2.0 * fresnel_moment_quadrature(eta, 1), 0.006) << eta;
    EXPECT_NEAR(3.0 * fresnel_moment2(eta), 3.0 * fresnel_moment_quadrature(eta, 2), 0.007) << eta;
    EXPECT_NEAR(diffuse_fresnel_reflectance(eta), 2.0 * fresnel_moment_quadrature(eta, 1), 0.006)
        << eta;
  }
  // Egan-Hilgeman at eta = 1.3 by hand: -1.44 / 1.69 + 0.71 / 1.3 + 0.668 + 0.0636 * 1.3
  // = -0.852071 + 0.546154 + 0.668 + 0.08268 = 0.444763; A = 1.444763 / 0.555237 = 2.602064.
  EXPECT_NEAR(diffuse_fresnel_reflectance(1.3), 0.44476284, 1e-8);
  EXPECT_NEAR(classical_boundary_a(1.3), 2.6020644, 1e-6);
  EXPECT_THROW(fresnel_moment1(3.0), InputError);
  EXPECT_THROW(better_boundary_a(0.4), InputError);
}

TEST(ClassicalDipole, HandValues) {
  // c = 0.9, g = 0, eta = 1, sigma_t = 1: alpha' = 0.9, D = 1/3, sigma_tr = sqrt(0.1 * 3)
  // = 0.5477226; F_dr(1) = 0.0016 -> A = 1.0032051; z_r = 1, z_v = 1 + 4 A / 3 = 2.3376068.
  // At r = 0.5: d_r = 1.1180340, d_v = 2.3904823, Bitterli eq. 2.37:
  // R = 0.9 / (4 pi) [1 (1 + 0.612372) e^-0.612372 / 1.397542 + 2.337607 (1 + 1.309300)
  //     e^-1.309300 / 13.660] = 0.0524321.
  const DipoleModel m = classical_dipole(HalfSpaceMedium::from_albedo(0.9, 0.0, 1.0));
  EXPECT_NEAR(m.image_height, 2.3376068376, 1e-9);
  EXPECT_NEAR(dipole_reflectance(m, 0.5), 0.0524320941, 1e-9);
  // Fluence at (0.5, 0) by eq. 2.33: 0.9 / (4 pi / 3) (e^-0.612372 / 1.118034 - e^-1.309300 /
  // 2.390482) = 0.0799033.
  EXPECT_NEAR(dipole_fluence(m, 0.5, 0.0), 0.0799033085, 1e-9);
  // Bitterli eq. 3.2: R_dr = 0.45 (1 + e^(-4/3 A sqrt 0.3)) e^(-sqrt 0.3) = 0.3852911.
  EXPECT_NEAR(dipole_total_reflectance(m), 0.3852911268, 1e-9);
}

TEST(BetterDipole, HandValues) {
  // c = 0.9, g = 0, eta = 1.33: C_1 = 0.2364770, C_2 = 0.1085507 (the fits), A = (1 + 3 C_2) /
  // (1 - 2 C_1) = 2.5152491; D = (0.2 + 0.9) / 3 = 0.3666667, sigma_tr = sqrt(0.1 / D) =
  // 0.5222330; z_v = 1 + 4 A D = 4.6890321; C_phi = 0.1317615, C_E = 0.3371739.
  // At r = 0.5, per unit strength: E = 0.0513504, phi = 0.1043440, and with the strength
  // alpha'^2 = 0.81, R = 0.81 (C_phi phi + C_E E) = 0.0251606.
  const DipoleModel m = better_dipole(HalfSpaceMedium::from_albedo(0.9, 0.0, 1.33));
  EXPECT_NEAR(m.strength, 0.81, 1e-15);
  EXPECT_NEAR(m.diffusion, 0.3666666667, 1e-9);
  EXPECT_NEAR(m.image_height, 4.6890320853, 1e-8);
  EXPECT_NEAR(dipole_reflectance(m, 0.5), 0.0251606589, 1e-9);
  // Total: 0.81 [C_E (e^-s z_r + e^-s z_v) / 2 + C_phi / (2 D s) (e^-s z_r - e^-s z_v)]
  // = 0.2340365.
  EXPECT_NEAR(dipole_total_reflectance(m), 0.2340364827, 1e-8);
}

TEST(Dipoles, AnnulusAveragesAddUpToTheTotal) {
  for (const double eta : {0.75, 1.0, 1.33, 2.5}) {
    for (const auto& m : {classical_dipole(HalfSpaceMedium::from_albedo(0.8, 0.3, eta)),
                          better_dipole(HalfSpaceMedium::from_albedo(0.8, 0.3, eta))}) {
      std::vector<double> edges{0.0};
      for (int i = 1; i <= 400; ++i) edges.push_back(0.25 * i * i / 400.0);  // to 1e4 / 400 = 25*...
      const auto average = dipole_reflectance_annulus_average(m, edges);
      double sum = 0.0;
      for (std::size_t i = 0; i < average.size(); ++i) {
        sum += average[i] * pi * (edges[i + 1] * edges[i + 1] - edges[i] * edges[i]);
      }
      const double tail = dipole_reflectance_annulus_integral(m, edges.back(), 1e6);
      EXPECT_NEAR(sum + tail, dipole_total_reflectance(m), 1e-10) << eta;
      // A thin annulus averages to the point value.
      EXPECT_NEAR(dipole_reflectance_annulus_average(m, std::vector<double>{1.0, 1.0 + 1e-6})[0],
                  dipole_reflectance(m, 1.0 + 5e-7), 1e-8 * dipole_reflectance(m, 1.0));
    }
  }
}

TEST(Dipoles, FluenceCellAveragesMatchAMidpointSum) {
  const DipoleModel m = better_dipole(HalfSpaceMedium::from_albedo(0.95, 0.0, 1.33));
  const std::vector<double> r_edges{0.5, 0.7}, z_edges{0.2, 0.6};
  const double average = dipole_fluence_cell_average(m, r_edges, z_edges)[0];
  // 200 x 200 midpoint rule of phi 2 pi r over the cell, by the point formula.
  double sum = 0.0;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double r = 0.5 + 0.2 * (i + 0.5) / n, z = 0.2 + 0.4 * (j + 0.5) / n;
      sum += dipole_fluence(m, r, z) * 2.0 * pi * r * (0.2 / n) * (0.4 / n);
    }
  }
  EXPECT_NEAR(average, sum / (pi * (0.49 - 0.25) * 0.4), 1e-5 * average);
}

TEST(GrosjeanBeam, PartsAgreeWithEachOther) {
  const GrosjeanBeam m = grosjean_beam(HalfSpaceMedium::from_albedo(0.9, 0.0, 1.3));
  // D = (2 * 0.1 + 0.9) / 3 = 0.3666667, the better dipole's.
  EXPECT_NEAR(m.diffusion, 1.1 / 3.0, 1e-12);
  std::vector<double> edges{0.0};
  for (int i = 1; i <= 200; ++i) edges.push_back(40.0 * (i / 200.0) * (i / 200.0));
  for (const ModelPart part : {ModelPart::single, ModelPart::multiple}) {
    const auto average = grosjean_beam_reflectance_annulus_average(m, edges, part);
    double sum = 0.0;
    for (std::size_t i = 0; i < average.size(); ++i) {
      sum += average[i] * pi * (edges[i + 1] * edges[i + 1] - edges[i] * edges[i]);
    }
    // The tail beyond 40 mfp is ~exp(-0.52 * 40) ~ 1e-9.
    const double total = grosjean_beam_total_reflectance(m, part);
    EXPECT_NEAR(sum, total, 1e-7) << static_cast<int>(part);
    EXPECT_NEAR(
        grosjean_beam_reflectance_annulus_average(m, std::vector<double>{1.0, 1.0 + 1e-5}, part)[0],
        grosjean_beam_reflectance(m, 1.0 + 5e-6, part), 1e-6 * average[20]);
  }
  EXPECT_NEAR(grosjean_beam_total_reflectance(m, ModelPart::all),
              grosjean_beam_total_reflectance(m, ModelPart::single) +
                  grosjean_beam_total_reflectance(m, ModelPart::multiple),
              1e-12);
  // Fluence cell average against a midpoint sum of point values away from the axis.
  const std::vector<double> r_edges{0.4, 0.6}, z_edges{0.5, 1.0};
  const double cell = grosjean_beam_fluence_cell_average(m, r_edges, z_edges)[0];
  double point_sum = 0.0;
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double r = 0.4 + 0.2 * (i + 0.5) / n, z = 0.5 + 0.5 * (j + 0.5) / n;
      point_sum += grosjean_beam_fluence(m, r, z) * 2.0 * pi * r * (0.2 / n) * (0.5 / n);
    }
  }
  EXPECT_NEAR(cell, point_sum / (pi * (0.36 - 0.16) * 0.5), 1e-4 * cell);
}

TEST(GrosjeanBeam, EscapeIsHalfE2IndexMatched) {
  // At eta = 1, P(z') = (1/2) int_0^1 exp(-x / mu) dmu = E_2(x) / 2 = (e^-x - x E_1(x)) / 2
  // (Abramowitz & Stegun 5.1.14), E_1(x) = -Ei(-x).
  const GrosjeanBeam m = grosjean_beam(HalfSpaceMedium::from_albedo(0.7, 0.0, 1.0));
  for (const double x : {0.0, 1e-4, 0.01, 0.3, 1.0, 3.0, 10.0, 30.0}) {
    const double e2 = x == 0.0 ? 1.0 : std::exp(-x) + x * std::expint(-x);
    EXPECT_NEAR(grosjean_beam_escape(m, x), 0.5 * e2, 1e-8) << x;  // 48 points (header)
  }
}

TEST(GrosjeanBeam, OnceScatteredPartIsTheExactSolutionAtGZero) {
  // At g = 0 the straight path is the only once-scattered one, so the beam's single part is the
  // refractive single-scatter solver's R_1 (an independent quadrature, over exit angle), less
  // the entry transmittance that the solver includes.
  const std::vector<double> edges{0.0, 0.1, 0.3, 1.0, 3.0, 10.0};
  for (const double eta : {1.0, 1.3, 1.5, 0.8}) {
    const GrosjeanBeam m = grosjean_beam(HalfSpaceMedium::from_albedo(0.9, 0.0, eta));
    const SingleScatterReflectance exact = half_space_single_scatter_reflectance(
        Medium::from_albedo(0.9, 1.0, 0.0), eta, edges, 1e-10);
    const double entry = fresnel_dielectric_transmittance(1.0, eta);
    const auto single = grosjean_beam_reflectance_annulus_average(m, edges, ModelPart::single);
    for (std::size_t i = 0; i < single.size(); ++i) {
      EXPECT_NEAR(entry * single[i], exact.mean[i], 1e-6 * exact.mean[i]) << eta << " " << i;
    }
    EXPECT_NEAR(entry * grosjean_beam_total_reflectance(m, ModelPart::single), exact.total,
                1e-7 * exact.total)
        << eta;
  }
}

TEST(GrosjeanBeam, ConservesEnergy) {
  // Nothing absorbed, all power leaves (header): R_dr = 1; below 1 whenever something is.
  for (const double eta : {0.75, 1.0, 1.3, 1.5}) {
    EXPECT_NEAR(grosjean_beam_total_reflectance(
                    grosjean_beam(HalfSpaceMedium::from_albedo(1.0, 0.0, eta)), ModelPart::all),
                1.0, 1e-6)
        << eta;
    for (const double c : {0.5, 0.9, 0.99, 0.999}) {
      for (const double g : {0.0, 0.5, 0.9}) {
        const double total = grosjean_beam_total_reflectance(
            grosjean_beam(HalfSpaceMedium::from_albedo(c, g, eta)), ModelPart::all);
        EXPECT_LT(total, 1.0) << c << " " << g << " " << eta;
        EXPECT_GT(total, 0.0);
      }
    }
  }
}

TEST(HalfSpaceModels, ExtremesAreNeverNaN) {
  const std::vector<double> r_edges{0.0, 0.05, 0.5, 2.0};
  const std::vector<double> z_edges{0.0, 0.1, 1.0};
  for (const double c : {0.0, 1e-6, 0.5, 0.9999, 1.0}) {
    for (const double g : {-0.999, 0.0, 0.999}) {
      for (const double eta : {0.75, 1.0, 1.0001, 1.33, 2.5}) {
        const HalfSpaceMedium medium = HalfSpaceMedium::from_albedo(c, g, eta);
        for (const DipoleModel& m : {classical_dipole(medium), better_dipole(medium)}) {
          const double r0 = dipole_reflectance(m, 0.0);
          EXPECT_TRUE(std::isfinite(r0) && r0 >= 0.0) << c << " " << g << " " << eta;
          EXPECT_FALSE(std::isnan(dipole_fluence(m, 0.0, m.source_depth)));  // +inf at the source
          const double total = dipole_total_reflectance(m);
          EXPECT_TRUE(total >= 0.0 && total <= 1.0 + 1e-9) << c << " " << g << " " << eta;
          for (double v : dipole_reflectance_annulus_average(m, r_edges)) EXPECT_TRUE(std::isfinite(v));
          for (double v : dipole_fluence_cell_average(m, r_edges, z_edges)) EXPECT_TRUE(std::isfinite(v));
        }
        if (g != 0.0 && eta != 1.33) continue;  // the Grosjean beam costs more: a subset
        const GrosjeanBeam beam = grosjean_beam(medium);
        EXPECT_FALSE(std::isnan(grosjean_beam_reflectance(beam, 0.0, ModelPart::all)));
        EXPECT_TRUE(std::isfinite(grosjean_beam_reflectance(beam, 0.3, ModelPart::all)));
        const double total = grosjean_beam_total_reflectance(beam, ModelPart::all);
        EXPECT_TRUE(total >= 0.0 && total <= 1.0 + 1e-6) << c << " " << g << " " << eta << " " << total;
        for (double v : grosjean_beam_reflectance_annulus_average(beam, r_edges, ModelPart::all)) {
          EXPECT_TRUE(std::isfinite(v));
        }
      }
    }
  }
  // At albedo 1 (sigma_a = 0) the classical dipole reflects everything: R_dr = alpha' = 1.
  EXPECT_NEAR(dipole_total_reflectance(classical_dipole(HalfSpaceMedium::from_albedo(1.0, 0.0, 1.33))),
              1.0, 1e-12);
}

TEST(HalfSpaceModels, RejectBadInput) {
  const DipoleModel m = classical_dipole(HalfSpaceMedium::from_albedo(0.5, 0.0, 1.0));
  EXPECT_THROW(dipole_fluence(m, 0.1, -0.5), InputError);
  EXPECT_THROW(dipole_reflectance(m, -1.0), InputError);
  EXPECT_THROW(dipole_reflectance_annulus_average(m, std::vector<double>{1.0, 0.5}), InputError);
  EXPECT_THROW(HalfSpaceMedium::from_albedo(1.5, 0.0, 1.0), InputError);
  EXPECT_THROW(HalfSpaceMedium::from_albedo(0.5, 1.0, 1.0), InputError);
}

}  // namespace
}  // namespace scatterlab
