#pragma once
// The medium of the half-space models: z > 0, lit at the origin by a pencil beam along +z
// (the searchlight problem, Bitterli §2.3), with relative index eta = n_medium / n_outside.
// Coefficients are in 1 / length for any one length unit (mfp when sigma_t = 1); every model
// answer is in that unit. The similarity relations (Bitterli eqs. 2.23-2.24) give the reduced
// quantities the diffusion models work with.

namespace scatterlab {

struct HalfSpaceMedium {
  double sigma_a = 0.0;  // absorption coefficient, >= 0
  double sigma_s = 1.0;  // scattering coefficient, >= 0, sigma_a + sigma_s > 0
  double g = 0.0;        // Henyey-Greenstein mean cosine, |g| < 1
  double eta = 1.0;      // relative index of refraction, in [0.5, 2.5]

  // albedo c in [0, 1] with sigma_t = 1 (lengths in mfp).
  static HalfSpaceMedium from_albedo(double albedo, double g, double eta);

  double sigma_t() const { return sigma_a + sigma_s; }
  double reduced_sigma_s() const { return sigma_s * (1.0 - g); }              // sigma_s'
  double reduced_sigma_t() const { return sigma_a + reduced_sigma_s(); }      // sigma_t'
  double reduced_albedo() const { return reduced_sigma_s() / reduced_sigma_t(); }  // alpha'

  // Throws InputError naming "sigma_a", "sigma_s", "g" or "eta" and what is accepted.
  void validate() const;
};

}  // namespace scatterlab
