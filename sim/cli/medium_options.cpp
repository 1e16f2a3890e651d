#include "medium_options.hpp"

#include "scatterlab/core/error.hpp"

namespace scatterlab::cli {

void add_medium_options(CLI::App& command, MediumOptions& o) {
  command.add_option("--material", o.material,
                     "Measured medium by name, from data/materials: jensen2001 (apple, marble, "
                     "skin1, wholemilk, ...; sigma_s' only, so g = 0 unless --g) or "
                     "narasimhan2006 (regular_milk, espresso, merlot, ...; with g). Needs "
                     "--channel; lengths are then in the table's unit, mm");
  command.add_option("--channel", o.channel,
                     "The material's colour channel: red, green or blue (one run per channel)");
  command.add_option("--length-unit", o.length_unit,
                     "Unit of the grid, the escape radius and 1/sigma_t: mfp (sigma_t = 1), um, "
                     "mm, cm or m; with a material, its table's unit unless given");
}

std::optional<double> apply_medium_options(const CLI::App& command, const MediumOptions& o,
                                           double albedo, double g, double sigma_t,
                                           std::optional<MaterialRequest> request, Medium& medium,
                                           std::optional<MaterialOrigin>& origin) {
  auto given = [&command](const char* flag) { return command.get_option(flag)->count() > 0; };
  if (given("--material")) {
    if (!request) {
      // The scene's medium is replaced; a physical unit its grid was written in stays.
      request = MaterialRequest{};
      if (is_physical_length_unit(medium.length_unit)) request->length_unit = medium.length_unit;
    }
    request->name = o.material;
  }
  if (request) {
    for (const char* flag : {"--albedo", "--sigma-t"}) {
      if (given(flag)) {
        throw InputError(flag, "given with a material (--material or medium.material)",
                         "either a material, with --channel and optionally --g and "
                         "--length-unit, or --albedo and --sigma-t");
      }
    }
    // A missing channel is the flag's to give (a scene's material without one fails on reading).
    const bool channel_from_flags = given("--channel") || !request->channel;
    if (given("--channel")) request->channel = o.channel;
    if (given("--length-unit")) request->length_unit = o.length_unit;
    if (given("--g")) request->g = g;
    const MaterialFields fields{given("--material") ? "--material" : "medium.material",
                                channel_from_flags ? "--channel" : "medium.channel",
                                given("--length-unit") ? "--length-unit" : "medium.length_unit",
                                given("--g") ? "--g" : "medium.g"};
    const ResolvedMaterial resolved = resolve_material(*request, fields);
    medium = resolved.medium;
    origin = resolved.origin;
    return resolved.eta;
  }
  if (given("--channel")) {
    throw InputError("--channel", "given without a material",
                     "--channel with --material NAME (or medium.material in the scene)");
  }
  if (given("--length-unit")) medium.length_unit = o.length_unit;
  if (given("--albedo")) medium.albedo = albedo;
  if (given("--g")) medium.g = g;
  if (given("--sigma-t")) medium.sigma_t = sigma_t;
  return std::nullopt;
}

}  // namespace scatterlab::cli
