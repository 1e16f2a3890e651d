#pragma once
// A homogeneous medium, validated once when it is made. Transport works in units of the mean
// free path (sigma_t = 1); sigma_t is kept so that physical lengths can be recovered.

#include <string>

namespace scatterlab {

struct Medium {
  double albedo = 0.5;   // single-scattering albedo sigma_s / sigma_t, in [0, 1]
  double sigma_t = 1.0;  // extinction coefficient, > 0, in 1 / length_unit
  double g = 0.9;        // Henyey-Greenstein mean cosine, |g| < 1
  std::string length_unit = "mfp";

  // (sigma_a, sigma_s, g) in 1 / length_unit; throws InputError naming the bad field.
  static Medium from_coefficients(double sigma_a, double sigma_s, double g,
                                  std::string length_unit = "mm");
  // (albedo, sigma_t, g); throws InputError naming the bad field.
  static Medium from_albedo(double albedo, double sigma_t, double g,
                            std::string length_unit = "mfp");

  double sigma_s() const { return albedo * sigma_t; }
  double sigma_a() const { return (1.0 - albedo) * sigma_t; }

  void validate() const;
};

}  // namespace scatterlab
