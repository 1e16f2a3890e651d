#pragma once

#include <numbers>

namespace scatterlab {

inline constexpr double pi = std::numbers::pi;
inline constexpr double inv_four_pi = 0.25 * std::numbers::inv_pi;
// The speed of light in vacuum, m/s (exact: the SI defines the metre by it).
inline constexpr double speed_of_light = 299'792'458.0;

}  // namespace scatterlab
