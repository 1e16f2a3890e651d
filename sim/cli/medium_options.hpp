#pragma once
// The medium flags simulate and searchlight share: --material, --channel and --length-unit
// (io/material_presets.hpp, transport/length_units.hpp). --albedo, --g and --sigma-t stay with
// each command, which reads them into `MediumFlags` for apply_medium_options.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/io/material_presets.hpp"

namespace scatterlab::cli {

struct MediumOptions {
  std::string material, channel, length_unit;
};

// Registers --material, --channel and --length-unit.
void add_medium_options(CLI::App& command, MediumOptions& options);

// The medium's flags laid over the scene's medium (flags override the file). With a material in
// effect (--material, or the scene's medium.material) the medium is resolved again from it with
// --channel, --length-unit and --g laid over the scene's keys, and --albedo and --sigma-t are
// refused (the material sets them); the material's eta is returned. Without one, --channel is
// refused, --length-unit, --albedo, --g and --sigma-t set the medium, and nullopt is returned.
// Throws InputError naming the flag or key.
std::optional<double> apply_medium_options(const CLI::App& command, const MediumOptions& options,
                                           double albedo, double g, double sigma_t,
                                           std::optional<MaterialRequest> scene_material,
                                           Medium& medium, std::optional<MaterialOrigin>& origin);

}  // namespace scatterlab::cli
