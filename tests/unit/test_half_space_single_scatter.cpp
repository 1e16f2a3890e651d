// The searchlight half-space's exact once-scattered reflectance: the general refractive solver
// reproduces its exit kernel at a flat boundary; bin averages sum to the closed-form total;
// eta = 1 isotropic reproduces albedo (1 - ln 2) / 2; bad input is refused.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/refract/path_contribution.hpp"
#include "scatterlab/refract/refractive_solver.hpp"

namespace scatterlab {
namespace {

TEST(HalfSpaceSingleScatter, SolverReproducesTheExitKernel) {
  // Medium z > 0 is our "inside" with outward normal -z: a flat square facing -z. By reciprocity
  // the exitance at surface radius r from a unit-intensity source at depth z is what the solver
  // carries from V to a detector L just outside: E_perp = T / D (no eta^2: the source is inside),
  // projected on the surface: E_perp cos(theta_L). Compare with p T cos^3 / z^2 exp(...).
  const Medium medium = Medium::from_albedo(0.8, 1.0, 0.6);
  const HenyeyGreenstein phase{medium.g};
  for (const double eta : {1.4, 0.8}) {
    const TriangleMesh plane = make_flat_square(100.0, -1);
    // Light goes from V (inside, index eta) out: the solver's medium index relative to outside
    // is eta, V inside, L outside.
    const RefractiveSolver solver(plane, eta);
    for (const double z : {0.3, 1.0, 2.5}) {
      for (const double r : {0.05, 0.4, 1.2}) {
        const double height = 1e-7;
        const auto paths = solver.find_paths(Vec3(0, 0, z), Light::point(Vec3(r, 0, -height)));
        const double theta = std::atan2(r, z);
        const double cos_i = std::cos(theta);
        const bool escapes = eta <= 1.0 || std::sin(theta) < 1.0 / eta;
        // Beyond the critical angle a grazing path to the detector still exists, carrying T -> 0.
        if (!escapes) continue;
        ASSERT_EQ(paths.size(), 1u);
        const RefractionPath& p = paths[0];
        const double d = refraction_distance_factor(solver.triangle(p.triangle), p, eta, false);
        const double exit_t = fresnel_dielectric_transmittance(-p.omega_v.dot(p.shading_normal), 1.0 / eta);
        const double solver_value = phase.evaluate(-cos_i) * exit_t *
                                    std::exp(-medium.sigma_t * p.distance_v) / d *
                                    p.omega_l.dot(p.shading_normal);
        const double closed_form = phase.evaluate(-cos_i) *
                                   fresnel_dielectric_transmittance(cos_i, 1.0 / eta) *
                                   std::exp(-medium.sigma_t * z / cos_i) * std::pow(cos_i, 3) / (z * z);
        EXPECT_NEAR(solver_value / closed_form, 1.0, 1e-5) << eta << " " << z << " " << r;
      }
    }
  }
}

TEST(HalfSpaceSingleScatter, BinsSumToTheClosedFormTotal) {
  const Medium medium = Medium::from_albedo(0.9, 1.0, 0.7);
  for (const double eta : {1.0, 1.33, 0.8}) {
    std::vector<double> edges{0.0};
    for (int i = 1; i <= 40; ++i) edges.push_back(0.05 * i * i);  // out to 80 mfp
    const SingleScatterReflectance r = half_space_single_scatter_reflectance(medium, eta, edges);
    double sum = 0.0, error = 0.0;
    for (std::size_t b = 0; b < r.mean.size(); ++b) {
      const double area = pi * (edges[b + 1] * edges[b + 1] - edges[b] * edges[b]);
      sum += r.mean[b] * area;
      error += r.error[b] * area;
      EXPECT_GE(r.mean[b], 0.0);
      EXPECT_LE(r.error[b], 1e-6 * r.mean[b] + 1e-300);
    }
    // Beyond 80 mfp the once-scattered light is ~1e-6 of the total (the grazing tail).
    EXPECT_NEAR(sum / r.total, 1.0, 2e-5) << eta;
    EXPECT_LT(error, 1e-6 * r.total);
  }
}

TEST(HalfSpaceSingleScatter, UnitIndexIsotropicTotal) {
  // eta = 1, isotropic: R1 = albedo int_0^1 mu / (2 (1 + mu)) dmu = albedo (1 - ln 2) / 2.
  const Medium medium = Medium::from_albedo(0.7, 2.0, 0.0);
  const std::vector<double> edges{0.0, 1.0};
  const SingleScatterReflectance r = half_space_single_scatter_reflectance(medium, 1.0, edges);
  EXPECT_NEAR(r.total, 0.7 * (1.0 - std::log(2.0)) / 2.0, 1e-12);
}

// The bin averages integrate over the exit angle with the depth in closed form; the pointwise
// R1(r) integrates over depth. Integrating R1(r) 2 pi r over each annulus is the second,
// independent path: inner and outer annuli, a thin one, forward and backward scattering, a
// critical angle and none.
TEST(HalfSpaceSingleScatter, BinAverageMatchesPointwiseExitance) {
  const std::vector<double> edges{0.0, 0.05, 0.4, 0.5, 3.0, 3.001, 9.5, 10.0};
  for (const double g : {0.0, 0.5, -0.3, 0.95}) {
    for (const double eta : {1.0, 1.33, 0.8, 1.5}) {
      const Medium medium = Medium::from_albedo(0.9, 2.0, g);
      const SingleScatterReflectance binned =
          half_space_single_scatter_reflectance(medium, eta, edges);
      for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
        if (b == 2 || b == 4) continue;  // the gaps between the annuli checked
        const double r0 = edges[b], r1 = edges[b + 1];
        const QuadratureResult power = integrate_adaptive(
            [&](double r) {
              return 2.0 * pi * r * half_space_single_scatter_exitance(medium, eta, r).value;
            },
            r0, r1, QuadratureOptions{0.0, 1e-10, 200});
        const double pointwise = power.value / (pi * (r1 * r1 - r0 * r0));
        EXPECT_NEAR(binned.mean[b] / pointwise, 1.0, 1e-7)
            << "g " << g << ", eta " << eta << ", [" << r0 << ", " << r1 << ")";
        EXPECT_LE(binned.error[b], 1e-8 * binned.mean[b]);
      }
    }
  }
}

TEST(HalfSpaceSingleScatter, RefusesBadInput) {
  const Medium medium = Medium::from_albedo(0.9, 1.0, 0.5);
  const std::vector<double> decreasing{0.0, 1.0, 0.5};
  EXPECT_THROW(half_space_single_scatter_reflectance(medium, 1.3, decreasing), InputError);
  const std::vector<double> one{1.0};
  EXPECT_THROW(half_space_single_scatter_reflectance(medium, 1.3, one), InputError);
  const std::vector<double> fine{0.0, 1.0};
  EXPECT_THROW(half_space_single_scatter_reflectance(medium, -1.0, fine), InputError);
  EXPECT_THROW(half_space_single_scatter_exitance(medium, 1.3, 0.0), InputError);
}

}  // namespace
}  // namespace scatterlab
