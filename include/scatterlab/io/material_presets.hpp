#pragma once
// Material presets: measured coefficients with their units and source, in TOML files under
// data/materials/ (jensen2001.toml, narasimhan2006.toml), compiled into the program. Read
// strictly: unknown keys, wrong types, negative coefficients, |g| >= 1 or arrays whose length
// differs from the channel list are an InputError naming the dotted key (e.g.
// "materials.apple.sigma_a") and what is accepted.
//
//   [source]  citation (string), length_unit ("um" | "mm" | "cm" | "m"), eta (number),
//             channels (array of names)
//   [materials.<name>]  sigma_a and exactly one of
//               sigma_s_reduced  (sigma_s (1 - g), when the source gives no g: Jensen 2001), or
//               sigma_s with g   (the source's scattering coefficient and HG mean cosine:
//                                 Narasimhan 2006),
//             each an array with one value per channel, coefficients >= 0 in 1/length_unit;
//             diffuse_reflectance (optional, the source's R_d per channel)

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scatterlab/core/medium.hpp"

namespace scatterlab {

struct MaterialPreset {
  std::string name;
  std::vector<double> sigma_s_reduced;      // per channel, 1 / length_unit; or empty
  std::vector<double> sigma_s;              // per channel, 1 / length_unit; or empty
  std::vector<double> g;                    // per channel with sigma_s; empty with sigma_s_reduced
  std::vector<double> sigma_a;              // per channel, 1 / length_unit
  std::vector<double> diffuse_reflectance;  // per channel, or empty
};

struct MaterialLibrary {
  std::string id;  // the file's stem, e.g. "jensen2001": qualifies names ("jensen2001/apple")
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

// The tables of data/materials/, as compiled into the program, in file-name order; parsed once.
const std::vector<MaterialLibrary>& shipped_material_libraries();

// A medium asked for by name, as a scene's [medium] table or the flags say it.
struct MaterialRequest {
  std::string name;                        // "apple", or qualified: "jensen2001/apple"
  std::optional<std::string> channel;      // one of the table's channels: required
  std::optional<std::string> length_unit;  // "um" | "mm" | "cm" | "m"; the table's when unset
  std::optional<double> g;                 // replaces the table's g (see resolve_material)
};

// The names errors use for each part of the request: the TOML keys or the flags.
struct MaterialFields {
  std::string material, channel, length_unit, g;
};

struct ResolvedMaterial {
  Medium medium;  // in the requested (or the table's) length unit
  MaterialOrigin origin;
  double eta = 1.0;  // the table's relative index of refraction
};

// The medium of one channel of a named material. Names are matched ignoring case, spaces, hyphens
// and underscores ("Regular Milk" is regular_milk, "skim milk" skimmilk). Every library is searched: a
// name in two libraries must be qualified, an unknown name is one InputError naming
// fields.material that lists the accepted names and the nearest one ("did you mean").
//   sigma_s and g given (Narasimhan): sigma_s and sigma_a as tabulated; g from the table unless
//     the request sets it (then only g changes).
//   sigma_s_reduced only (Jensen): the table measured sigma_s' = sigma_s (1 - g) alone, so g
//     is free. By default g = 0 and sigma_s = sigma_s'; a requested g keeps the measured
//     sigma_s' and takes sigma_s = sigma_s' / (1 - g) (the similarity relation, Wyman et al.
//     1989; Bitterli 2013 eqs. 2.23-2.24), which leaves the diffusion-regime light unchanged.
// Coefficients are converted from the table's unit to the requested one: a coefficient in 1/mm
// is 10 times larger in 1/cm.
ResolvedMaterial resolve_material(
    const MaterialRequest& request, const MaterialFields& fields,
    const std::vector<MaterialLibrary>& libraries = shipped_material_libraries());

}  // namespace scatterlab
