#pragma once

#include <numbers>

namespace scatterlab {

inline constexpr double pi = std::numbers::pi;
inline constexpr double inv_four_pi = 0.25 * std::numbers::inv_pi;

}  // namespace scatterlab
