// Fresnel reflectance and refraction at a smooth dielectric interface (core/fresnel.hpp) against
// values that follow directly from Born & Wolf §1.5: normal incidence, Brewster's angle, the
// critical angle, grazing incidence, eta = 1, Stokes reciprocity, and a value worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scatterlab/core/fresnel.hpp"

namespace scatterlab {
namespace {

TEST(Fresnel, NormalIncidenceIsTheSquaredIndexContrast) {
  for (double eta : {1.0001, 1.33, 1.5, 2.5, 0.75, 1.0 / 1.33}) {
    const double expected = std::pow((eta - 1.0) / (eta + 1.0), 2);
    EXPECT_NEAR(fresnel_dielectric_reflectance(1.0, eta), expected, 1e-15) << "eta " << eta;
  }
}

TEST(Fresnel, IndexMatchedInterfaceReflectsNothingAndBendsNothing) {
  for (double cos_i : {0.0, 1e-9, 0.3, 0.7, 1.0}) {
    const FresnelDielectric terms = fresnel_dielectric_terms(cos_i, 1.0);
    EXPECT_EQ(terms.reflectance(), 0.0);
    EXPECT_EQ(terms.cos_transmitted, cos_i);
    EXPECT_FALSE(terms.total_internal_reflection);
  }
}

TEST(Fresnel, HandWorkedValueAtFortyFiveDegreesIntoGlass) {
  // eta = 1.5, 45 deg: cos t = sqrt(1 - 0.5 / 2.25) = 0.881917; r_s = -0.303337,
  // r_p = 0.0920133 (Born & Wolf eq. (21)), so R_s = 0.0920134, R_p = 0.00846645.
  const FresnelDielectric terms = fresnel_dielectric_terms(std::sqrt(0.5), 1.5);
  EXPECT_NEAR(terms.cos_transmitted, 0.8819171037, 1e-9);
  EXPECT_NEAR(terms.reflectance_s, 0.0920134, 1e-7);
  EXPECT_NEAR(terms.reflectance_p, 0.00846645, 1e-8);
  // Abeles' relation: at 45 degrees R_p = R_s^2 for any index.
  EXPECT_NEAR(terms.reflectance_p, terms.reflectance_s * terms.reflectance_s, 1e-16);
  EXPECT_NEAR(terms.reflectance(), 0.0502399, 1e-7);
}

TEST(Fresnel, PPolarisationVanishesAtBrewstersAngle) {
  for (double eta : {1.33, 2.5, 0.75}) {
    const double brewster = std::atan(eta);  // tan theta_B = n_t / n_i
    const FresnelDielectric terms = fresnel_dielectric_terms(std::cos(brewster), eta);
    EXPECT_NEAR(terms.reflectance_p, 0.0, 1e-28) << "eta " << eta;
    EXPECT_GT(terms.reflectance_s, 0.01);
    // Reflected and refracted rays are perpendicular there: theta_i + theta_t = pi / 2.
    EXPECT_NEAR(std::acos(terms.cos_transmitted) + brewster, 0.5 * std::numbers::pi, 1e-12);
  }
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
  const double eta = 1.0 / 1.33;  // leaving water
  const double critical = std::asin(eta);
  for (double angle : {critical + 1e-9, critical + 0.1, 1.2, 0.5 * std::numbers::pi}) {
    const FresnelDielectric terms = fresnel_dielectric_terms(std::cos(angle), eta);
    EXPECT_TRUE(terms.total_internal_reflection) << angle;
    EXPECT_EQ(terms.reflectance(), 1.0);
    EXPECT_EQ(terms.cos_transmitted, 0.0);
  }
  // Just inside the critical angle light still gets out, grazing, with F < 1 but close to it.
  const FresnelDielectric inside = fresnel_dielectric_terms(std::cos(critical - 1e-6), eta);
  EXPECT_FALSE(inside.total_internal_reflection);
  EXPECT_LT(inside.reflectance(), 1.0);
  EXPECT_GT(inside.reflectance(), 0.9);
  EXPECT_LT(inside.cos_transmitted, 1e-2);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
  for (double eta : {1.0001, 1.33, 2.5}) EXPECT_EQ(fresnel_dielectric_reflectance(0.0, eta), 1.0);
  EXPECT_GT(fresnel_dielectric_reflectance(1e-6, 1.33), 0.9999);
}

TEST(Fresnel, ReciprocityBetweenBothSidesOfTheInterface) {
  // Stokes: the reflectance is the same seen from either side along the same ray pair.
  for (double eta : {1.33, 2.5}) {
    for (double cos_i : {0.05, 0.4, 0.9}) {
      const FresnelDielectric in = fresnel_dielectric_terms(cos_i, eta);
      const FresnelDielectric out = fresnel_dielectric_terms(in.cos_transmitted, 1.0 / eta);
      EXPECT_NEAR(out.reflectance(), in.reflectance(), 1e-13);
      EXPECT_NEAR(out.cos_transmitted, cos_i, 1e-14);
    }
  }
}

TEST(Fresnel, OutOfRangeCosinesAreClampedNotNaN) {
  EXPECT_EQ(fresnel_dielectric_reflectance(1.0 + 1e-15, 1.33),
            fresnel_dielectric_reflectance(1.0, 1.33));
  EXPECT_EQ(fresnel_dielectric_transmittance(1.0, 1.33),
            1.0 - fresnel_dielectric_reflectance(1.0, 1.33));
  EXPECT_EQ(fresnel_dielectric_reflectance(-1e-17, 1.33), 1.0);
}

TEST(Refract, FollowsSnellsLawAndStaysUnit) {
  const double eta = 1.33, theta = 0.6;
  const Vec3 incident(std::sin(theta), 0.0, std::cos(theta));  // travelling into z > 0
  Vec3 transmitted;
  ASSERT_TRUE(refract(incident, -Vec3::UnitZ(), eta, transmitted));
  EXPECT_NEAR(transmitted.norm(), 1.0, 1e-15);
  EXPECT_NEAR(transmitted.x() * eta, incident.x(), 1e-15);  // n1 sin i = n2 sin t
  EXPECT_EQ(transmitted.y(), 0.0);
  EXPECT_GT(transmitted.z(), incident.z());  // bent towards the normal
}

TEST(Refract, ReportsTotalInternalReflection) {
  const Vec3 incident(std::sin(1.2), 0.0, -std::cos(1.2));  // leaving water upwards at 69 deg
  Vec3 transmitted = Vec3::Zero();
  EXPECT_FALSE(refract(incident, Vec3::UnitZ(), 1.0 / 1.33, transmitted));
  EXPECT_EQ(transmitted, Vec3::Zero());
}

}  // namespace
}  // namespace scatterlab
