#pragma once
// Physical length units at the transport boundary (docs/architecture.md, "Units").
//
// A spec holds its lengths (grid edges, escape radius) and its medium's sigma_t in one unit,
// medium.length_unit: "mfp" (the default, sigma_t = 1) or a physical unit ("um", "mm", "cm",
// "m"). Transport always runs in mean free paths: a length L in the spec's unit is L sigma_t mfp
// (1 mfp = 1 / sigma_t). So the specs' transport_problem scales their lengths by sigma_t on the
// way in, and the engine converts each tally on the way out by its length dimension k (the
// length power of its Units, tally/units.hpp): a value q per mfp^k is q sigma_t^k per unit^k.
// In "mfp" nothing is scaled, so those runs are bit for bit what they always were.

#include <string>
#include <vector>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/tally/axis.hpp"
#include "scatterlab/tally/units.hpp"

namespace scatterlab {

// Throws InputError naming medium.length_unit unless it is "mfp" or a physical unit, or when it
// is "mfp" but sigma_t is not 1 (coefficients in a physical unit the scene did not name).
void check_length_unit(const Medium& medium);

// Mean free paths per unit of the spec's lengths: sigma_t in a physical unit, 1 in "mfp".
inline double mfp_per_length_unit(const Medium& medium) {
  return medium.length_unit == "mfp" ? 1.0 : medium.sigma_t;
}

// The span of a grid's length axes in mfp, so that every bin's width, ring area and shell volume,
// and a tally divided by them, stay finite and non-zero doubles: ends within +-1e12 mfp, bins at
// least 1e-12 mfp wide. (Past these, r.max = 1e-300 gives rings of zero area and NaN fluence, and
// z in [-1e308, 1e308] bins of infinite width.)
inline constexpr double max_grid_mfp = 1e12;
inline constexpr double min_bin_mfp = 1e-12;

// The one check of a length axis of any grid (r, z, rho), after its own (ends, bins): throws
// InputError naming grid.<name>.min or grid.<name>.max, with the accepted range in the spec's unit,
// unless the axis in mfp keeps to max_grid_mfp and min_bin_mfp.
void check_length_axis_span(const UniformAxis& axis, const std::string& name, const Medium& medium);

// A finite escape radius must stay finite in mfp: one that overflows would let photons of an
// albedo-1 medium walk forever. Throws InputError naming run.escape_radius.
void check_escape_radius_span(double escape_radius, const Medium& medium);

// A length axis of the spec in mfp: its ends times `mfp_per_unit`, the same bins.
UniformAxis length_axis_in_mfp(const UniformAxis& axis, double mfp_per_unit);

// The unit a homogeneous medium's tallies are reported in: medium.length_unit, with sigma_t mfp
// to one of it (TransportProblem::length; TallyBook::finish converts each tally by its units).
inline ReportedLength reported_length(const Medium& medium) {
  return {medium.length_unit, mfp_per_length_unit(medium)};
}

}  // namespace scatterlab
