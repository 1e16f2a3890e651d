#pragma once
// A tally's units as numbers: the powers of watts, length, steradians, seconds and radians. The
// file's text ("W mfp^-2 sr^-1 per W incident") is written from them, and converting a tally from
// the walk's lengths to the scene's reads the length power, never the text.

#include <string>
#include <string_view>

namespace scatterlab {

struct Units {
  int watts = 1;       // 1: power (W), per unit of what is incident; 0: a length alone
  int length = 0;      // e.g. -2 for per unit area
  int steradians = 0;  // -1 for per steradian
  int seconds = 0;     // -1 for per second: a response to an impulse (per J incident)
  int radians = 0;     // -1 for per radian (of an azimuth alone)

  // "W mfp^-2 sr^-1 per W incident" for {1, -2, -1, 0} and length_unit "mfp"; "mm" for {0, 1}.
  std::string text(std::string_view length_unit) const;

  bool operator==(const Units&) const = default;
};

// The unit a run reports its tallies' lengths in: its name, and how many of the walk's length
// units (mfp in a homogeneous medium) make one of it (sigma_t in a physical unit, else 1).
struct ReportedLength {
  std::string unit = "mfp";
  double walk_per_unit = 1.0;

  // What turns a value in walk units into the reported unit: a value per mfp^k is
  // walk_per_unit^k per unit^k, so the factor is walk_per_unit^-length. 1 when nothing changes.
  double factor(const Units& units) const;
};

}  // namespace scatterlab
