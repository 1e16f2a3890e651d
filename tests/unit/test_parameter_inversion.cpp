// (R_dr, l_d) -> (sigma_a, sigma_s) and back, for every half-space model (Bitterli §3.4).
#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/core/error.hpp"
#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/grosjean_beam.hpp"
#include "scatterlab/models/quantized_diffusion.hpp"
#include "scatterlab/models/parameter_inversion.hpp"

namespace scatterlab {
namespace {

double forward_total(HalfSpaceModel model, const HalfSpaceMedium& medium) {
  switch (model) {
    case HalfSpaceModel::classical_dipole: return dipole_total_reflectance(classical_dipole(medium));
    case HalfSpaceModel::better_dipole: return dipole_total_reflectance(better_dipole(medium));
    case HalfSpaceModel::quantized_diffusion:
      return quantized_diffusion_total_reflectance(quantized_diffusion(medium));
    case HalfSpaceModel::grosjean_beam:
      return grosjean_beam_total_reflectance(grosjean_beam(medium), ModelPart::all);
  }
  return 0.0;
}

double forward_sigma_tr(HalfSpaceModel model, const HalfSpaceMedium& medium) {
  switch (model) {
    case HalfSpaceModel::classical_dipole: return classical_dipole(medium).sigma_tr;
    case HalfSpaceModel::better_dipole: return better_dipole(medium).sigma_tr;
    case HalfSpaceModel::quantized_diffusion: {
      const QuantizedDiffusion m = quantized_diffusion(medium);
      return std::sqrt(medium.sigma_a / m.diffusion);
    }
    case HalfSpaceModel::grosjean_beam: return grosjean_beam(medium).sigma_tr;
  }
  return 0.0;
}

TEST(ParameterInversion, RoundTripsThroughEachModel) {
  for (const auto model : all_half_space_models) {
    for (const double eta : {1.0, 1.3, 0.75}) {
      for (const double r_dr : {0.05, 0.3, 0.6, 0.85}) {
        for (const double g : {0.0, 0.8}) {
          const double l_d = 2.5;  // mm
          const InvertedCoefficients inv = invert_reflectance(model, r_dr, l_d, eta, g);
          const HalfSpaceMedium medium{inv.sigma_a, inv.sigma_s, g, eta};
          EXPECT_NEAR(forward_total(model, medium), r_dr, 1e-9) << to_string(model) << " " << eta;
          EXPECT_NEAR(1.0 / forward_sigma_tr(model, medium), l_d, 1e-9 * l_d) << to_string(model);
          EXPECT_NEAR(medium.reduced_albedo(), inv.reduced_albedo, 1e-12);
        }
      }
    }
  }
}

TEST(ParameterInversion, ClassicalDipoleByHand) {
  // Jensen's apple, red (data/materials/jensen2001.toml): sigma_s' = 2.29, sigma_a = 0.003 /mm,
  // eta = 1.3. alpha' = 2.29 / 2.293 = 0.998692; sigma_tr = sqrt(3 * 0.003 * 2.293) = 0.143656
  // -> l_d = 6.96107 mm; R_dr (Bitterli eq. 3.2, A = 2.602064) = 0.846. Inverting gives them back.
  const InvertedCoefficients inv =
      invert_reflectance(HalfSpaceModel::classical_dipole,
                         total_diffuse_reflectance(HalfSpaceModel::classical_dipole, 2.29 / 2.293, 1.3),
                         1.0 / std::sqrt(3.0 * 0.003 * 2.293), 1.3);
  EXPECT_NEAR(inv.sigma_a, 0.003, 1e-9);
  EXPECT_NEAR(inv.sigma_s, 2.29, 1e-8);
  EXPECT_NEAR(total_diffuse_reflectance(HalfSpaceModel::classical_dipole, 2.29 / 2.293, 1.3), 0.846,
              0.0005);
}

TEST(ParameterInversion, ModelsByName) {
  for (const auto model : all_half_space_models) {
    EXPECT_EQ(half_space_model_from_string(to_string(model), "model"), model);
  }
  EXPECT_THROW(half_space_model_from_string("grosjean", "model"), InputError);
}

TEST(ParameterInversion, RejectsWhatNoMediumReaches) {
  EXPECT_THROW(invert_reflectance(HalfSpaceModel::better_dipole, 0.0, 1.0, 1.3), InputError);
  // The better dipole reaches R_dr = C_E + 2 A C_phi = 1 exactly at alpha' = 1 (all power out).
  EXPECT_THROW(invert_reflectance(HalfSpaceModel::better_dipole, 1.0, 1.0, 1.3), InputError);
  EXPECT_THROW(invert_reflectance(HalfSpaceModel::classical_dipole, 0.5, 0.0, 1.3), InputError);
  EXPECT_THROW(invert_reflectance(HalfSpaceModel::classical_dipole, 0.5, 1.0, 1.3, 1.0), InputError);
}

}  // namespace
}  // namespace scatterlab
