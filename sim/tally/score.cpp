#include "scatterlab/tally/score.hpp"

#include <array>

namespace scatterlab {
namespace {

constexpr std::array<std::string_view, static_cast<std::size_t>(Score::count)> names = {
    "fluence",  "flux",           "radiance", "exitance",   "transmittance", "entry_reflectance",
    "absorbed", "absorbed_depth", "escaped",  "collisions", "path_length",   "exact"};

}  // namespace

std::string_view to_string(Score score) {
  return names.at(static_cast<std::size_t>(score));
}

std::optional<Score> score_named(std::string_view name) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<Score>(i);
  }
  return std::nullopt;
}

}  // namespace scatterlab
