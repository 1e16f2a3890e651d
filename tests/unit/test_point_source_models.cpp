// Classical diffusion and Grosjean's approximation for the infinite-medium point source: values
// computed by hand from the formulas, the moments Grosjean's D is built to preserve, the far
// field against the exact discrete mode, and the limits.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scatterlab/core/error.hpp"
#include "scatterlab/models/point_source_diffusion.hpp"
#include "scatterlab/models/point_source_exact.hpp"
#include "scatterlab/models/point_source_grosjean.hpp"

namespace scatterlab {
namespace {

TEST(PointSourceDiffusion, HandValue) {
  // c = 0.5, rho = 2: sigma_tr = sqrt(3 * 0.5) = 1.2247449, D = 1/3,
  // phi = exp(-2.4494897) / (4 pi * 2 / 3) = 0.0863488 / 8.3775804 = 0.01030580.
  EXPECT_NEAR(diffusion_point_source_fluence(0.5, 2.0), 0.010305795, 1e-9);
  EXPECT_NEAR(diffusion_decay_rate(0.5), 1.224744871, 1e-9);
}

TEST(PointSourceGrosjean, HandValue) {
  // c = 0.5, rho = 2: D = (2 - 0.5) / 3 = 0.5, sigma_tr = sqrt(0.5 / 0.5) = 1;
  // phi = exp(-2) / (4 pi 4) + 0.5 exp(-2) / (4 pi 0.5 2) = 0.0026924 + 0.0053848 = 0.0080772.
  EXPECT_NEAR(grosjean_point_source_fluence(0.5, 2.0), 0.0080772297, 1e-9);
  EXPECT_NEAR(grosjean_point_source_fluence(0.5, 2.0, false), 0.0053848198, 1e-9);
}

TEST(PointSourceModels, ConservePowerLikeTheExactSolution) {
  // Both approximations integrate to the exact number of collisions per photon, 1 / (1 - c),
  // and Grosjean's collided part to the exact c / (1 - c).
  for (const double c : {0.01, 0.3, 0.7, 0.99}) {
    const double inf = std::numeric_limits<double>::infinity();
    const double exact_collided = point_source_fluence_shell_integral(c, 0.0, inf, false);
    EXPECT_NEAR(exact_collided, c / (1.0 - c), 1e-9 * c / (1.0 - c));
    EXPECT_NEAR(grosjean_point_source_shell_integral(c, 0.0, inf, false), exact_collided,
                1e-9 * exact_collided);
    EXPECT_NEAR(grosjean_point_source_shell_integral(c, 0.0, inf), 1.0 / (1.0 - c),
                1e-9 / (1.0 - c));
    EXPECT_NEAR(diffusion_point_source_shell_integral(c, 0.0, 1e4), 1.0 / (1.0 - c),
                1e-9 / (1.0 - c));
  }
}

TEST(PointSourceGrosjean, PreservesTheSecondMomentOfTheCollidedFluence) {
  // int rho^2 phi_c dV / int phi_c dV = 2 (2 - c) / (1 - c) exactly (header derivation), for the
  // exact solution (integrated here shell by shell) and for Grosjean's kernel.
  for (const double c : {0.3, 0.8}) {
    double exact_moment = 0.0, grosjean_moment = 0.0;
    const double width = 0.05;
    for (int i = 0; i < 1600; ++i) {  // out to 80 mfp, beyond which exp(-rho / nu0) < 1e-9
      const double lo = i * width, hi = lo + width, mid = 0.5 * (lo + hi);
      // rho^2 over a thin shell ~ mid^2 + width^2 / 12 (shell average of rho^2, to O(width^2/rho^2)).
      const double r2 = mid * mid + width * width / 12.0;
      exact_moment += r2 * point_source_fluence_shell_integral(c, lo, hi, false);
      grosjean_moment += r2 * grosjean_point_source_shell_integral(c, lo, hi, false);
    }
    const double expected = 2.0 * (2.0 - c) / (1.0 - c) * c / (1.0 - c);
    EXPECT_NEAR(exact_moment / expected, 1.0, 2e-3) << c;
    EXPECT_NEAR(grosjean_moment / expected, 1.0, 2e-3) << c;
  }
}

TEST(PointSourceModels, FarFieldDecayApproachesTheDiscreteMode) {
  // At c = 0.99 the exact fluence decays as exp(-rho / nu0); diffusion's sigma_tr and Grosjean's
  // agree with 1 / nu0 to within the O(1 - c) correction of P1 theory: here 1 / nu0 = 0.171778,
  // sigma_tr = 0.173205 (+0.8%), Grosjean 0.172345 (+0.3%).
  const double exact_rate = 1.0 / discrete_eigenvalue(0.99);
  EXPECT_NEAR(diffusion_decay_rate(0.99) / exact_rate, 1.0, 0.01);
  EXPECT_NEAR(grosjean_decay_rate(0.99) / exact_rate, 1.0, 0.005);
  // And the curves themselves at 5 to 15 mfp are within 3% (diffusion) / 1.5% (Grosjean).
  for (const double rho : {5.0, 10.0, 15.0}) {
    const double exact = point_source_fluence(0.99, rho);
    EXPECT_NEAR(diffusion_point_source_fluence(0.99, rho) / exact, 1.0, 0.03) << rho;
    EXPECT_NEAR(grosjean_point_source_fluence(0.99, rho) / exact, 1.0, 0.015) << rho;
  }
  // At low albedo diffusion is far off (decay sqrt(3) instead of ~1) and Grosjean is exact.
  EXPECT_GT(diffusion_decay_rate(0.01), 1.7);
  EXPECT_NEAR(grosjean_point_source_fluence(0.01, 3.0) / point_source_fluence(0.01, 3.0), 1.0, 0.02);
}

TEST(PointSourceModels, ShellAveragesAreFiniteAtTheSourceAndMatchThinShells) {
  for (const double c : {0.0, 0.01, 0.5, 0.9999}) {
    const double d0 = diffusion_point_source_shell_average(c, 0.0, 0.1);
    const double g0 = grosjean_point_source_shell_average(c, 0.0, 0.1);
    EXPECT_TRUE(std::isfinite(d0) && d0 > 0.0) << c;
    EXPECT_TRUE(std::isfinite(g0) && g0 > 0.0) << c;
    // A thin shell's average is the point value at its middle.
    EXPECT_NEAR(diffusion_point_source_shell_average(c, 2.0, 2.0 + 1e-7) /
                    diffusion_point_source_fluence(c, 2.0 + 5e-8), 1.0, 1e-8) << c;  // 2.0 + 1e-7 - 2.0 is 1e-7 to ~1e-9
    EXPECT_NEAR(grosjean_point_source_shell_average(c, 2.0, 2.0 + 1e-7) /
                    grosjean_point_source_fluence(c, 2.0 + 5e-8), 1.0, 1e-6) << c;
  }
}

TEST(PointSourceModels, RejectBadInput) {
  EXPECT_THROW(diffusion_point_source_fluence(1.0, 1.0), InputError);
  EXPECT_THROW(diffusion_point_source_fluence(0.5, 0.0), InputError);
  EXPECT_THROW(grosjean_point_source_fluence(-0.1, 1.0), InputError);
  EXPECT_THROW(grosjean_point_source_shell_average(0.5, 1.0, 1.0), InputError);
  EXPECT_THROW(diffusion_point_source_shell_integral(0.5, -1.0, 1.0), InputError);
}

}  // namespace
}  // namespace scatterlab
