#pragma once
// Material presets: measured coefficients with their units and source, in TOML files under
// data/materials/ (e.g. jensen2001.toml). Read strictly: unknown keys, wrong types, negative
// coefficients or arrays whose length differs from the channel list are an InputError naming the
// dotted key (e.g. "materials.apple.sigma_a") and what is accepted.
//
//   [source]  citation (string), length_unit ("um" | "mm" | "cm" | "m"), eta (number),
//             channels (array of names)
//   [materials.<name>]  sigma_s_reduced, sigma_a (arrays of numbers >= 0, one per channel, in
//             1/length_unit), diffuse_reflectance (optional, the source's R_d per channel)

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace scatterlab {

struct MaterialPreset {
  std::string name;
  std::vector<double> sigma_s_reduced;      // per channel, 1 / length_unit
  std::vector<double> sigma_a;              // per channel, 1 / length_unit
  std::vector<double> diffuse_reflectance;  // per channel, or empty
};

struct MaterialLibrary {
  std::string citation;
  std::string length_unit;
  double eta = 1.0;
  std::vector<std::string> channels;
  std::vector<MaterialPreset> materials;  // in name order

  // Throws InputError("material", ...) listing the known names.
  const MaterialPreset& find(std::string_view name) const;
};

MaterialLibrary parse_material_library(std::string_view toml_text, const std::string& origin);
MaterialLibrary load_material_library(const std::filesystem::path& path);

}  // namespace scatterlab
