// scatterlab materials [NAME]: the measured media compiled into the program
// (io/material_presets.hpp), which a scene's medium.material and --material name: every table
// with its source, unit, index, channels and material names, or one material's coefficients.
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "scatterlab/io/material_presets.hpp"

namespace scatterlab::cli {
namespace {

void print_library(const MaterialLibrary& library) {
  fmt::print("{}: {}\n  lengths in {}, eta {}, channels {}\n", library.id, library.citation,
             library.length_unit, library.eta, fmt::join(library.channels, ", "));
  std::string line = " ";
  for (const MaterialPreset& preset : library.materials) {
    if (line.size() + preset.name.size() + 1 > 96) {
      fmt::print("{}\n", line);
      line = " ";
    }
    line += " " + preset.name;
  }
  fmt::print("{}\n", line);
}

// One row of a material's table: a quantity and its value per channel.
void print_row(const std::string& quantity, const std::vector<double>& values) {
  if (values.empty()) return;
  fmt::print("  {:<24}", quantity);
  for (const double value : values) fmt::print("{:>12.6g}", value);
  fmt::print("\n");
}

void print_material(const MaterialLibrary& library, const MaterialPreset& preset) {
  const std::string per = "1/" + library.length_unit;
  fmt::print("{}/{}: {} (eta {})\n", library.id, preset.name, library.citation, library.eta);
  fmt::print("  {:<24}", "channel");
  for (const std::string& channel : library.channels) fmt::print("{:>12}", channel);
  fmt::print("\n");
  print_row("sigma_a [" + per + "]", preset.sigma_a);
  print_row("sigma_s [" + per + "]", preset.sigma_s);
  print_row("sigma_s' [" + per + "]", preset.sigma_s_reduced);
  print_row("g", preset.g);
  print_row("R_d (measured)", preset.diffuse_reflectance);
}

}  // namespace

Action add_materials_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "materials",
      "The measured media a scene's medium.material or --material names (data/materials): "
      "every table with its source, length unit, index and channels, and its materials; with "
      "NAME, that material's coefficients per channel");
  auto name = std::make_shared<std::string>();
  command->add_option("NAME", *name,
                      "A material, as a scene names it: case, spaces, hyphens and underscores "
                      "are ignored; table/name where two tables hold it");
  return [name] {
    const std::vector<MaterialLibrary>& libraries = shipped_material_libraries();
    if (name->empty()) {
      for (const MaterialLibrary& library : libraries) print_library(library);
      return 0;
    }
    // The reader's own lookup, so that a name is found (or refused, with the nearest) as in a
    // scene; any channel finds the material.
    const MaterialOrigin origin =
        resolve_material({*name, libraries.front().channels.front(), {}, {}},
                         {"NAME", "--channel", "--length-unit", "--g"}, libraries)
            .origin;
    for (const MaterialLibrary& library : libraries) {
      if (library.id != origin.library) continue;
      const auto preset =
          std::find_if(library.materials.begin(), library.materials.end(),
                       [&](const MaterialPreset& p) { return p.name == origin.name; });
      print_material(library, *preset);
    }
    return 0;
  };
}

}  // namespace scatterlab::cli
