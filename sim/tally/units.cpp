#include "scatterlab/tally/units.hpp"

#include <fmt/format.h>

#include <cmath>

namespace scatterlab {
namespace {

// " unit" for power 1, " unit^k" otherwise, "" for 0.
std::string power_of(std::string_view unit, int power) {
  if (power == 0) return "";
  if (power == 1) return fmt::format(" {}", unit);
  return fmt::format(" {}^{}", unit, power);
}

}  // namespace

std::string Units::text(std::string_view length_unit) const {
  std::string text = watts != 0 ? "W" : "";
  text += power_of(length_unit, length);
  text += power_of("sr", steradians);
  text += power_of("rad", radians);
  if (watts != 0) text += seconds == -1 ? " per J incident" : " per W incident";
  return text.starts_with(' ') ? text.substr(1) : text;
}

double ReportedLength::factor(const Units& units) const {
  if (units.length == 0 || walk_per_unit == 1.0) return 1.0;
  return std::pow(walk_per_unit, -units.length);
}

}  // namespace scatterlab
