#pragma once
// A homogeneous medium, validated once when it is made. Transport works in units of the mean
// free path (sigma_t = 1); sigma_t is kept so that physical lengths can be recovered.
//
// length_unit is "mfp" (sigma_t = 1 by definition) or a physical unit, "um", "mm", "cm" or "m",
// in which sigma_t is given and in which the spec's grid and the file's lengths are read
// (transport/length_units.hpp converts at the transport boundary).

#include <string>
#include <string_view>

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

// Whether `unit` is one of the physical length units "um", "mm", "cm", "m".
bool is_physical_length_unit(std::string_view unit);

// Millimetres in one `unit` ("um": 1e-3, "mm": 1, "cm": 10, "m": 1000); throws InputError for
// "length_unit" when `unit` is not physical.
double millimetres_per(std::string_view unit);

// Where a medium's coefficients came from when they came from a measured table
// (data/materials/*.toml, io/material_presets.hpp): written to the file's /parameters.
struct MaterialOrigin {
  std::string name;      // the table's key, e.g. "apple"
  std::string library;   // the table's file stem, e.g. "jensen2001"
  std::string channel;   // e.g. "red"
  std::string citation;  // the table's [source] citation
  std::string note;      // how g and sigma_s were chosen (e.g. the similarity relation)
};

}  // namespace scatterlab
