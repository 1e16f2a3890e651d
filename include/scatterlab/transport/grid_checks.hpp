#pragma once
// The checks every spec makes of its grid's axes, each naming grid.<name>.<key> and what it
// accepts (the infinite medium's, the searchlight's and the slab's grids).

#include <string>

#include "scatterlab/tally/axis.hpp"

namespace scatterlab {

inline constexpr int max_axis_bins = 100'000;

// grid.<name>.bins in [1, max_axis_bins].
void check_bins(const UniformAxis& axis, const std::string& name);

// An axis that starts at 0 by construction (r from the beam, z from the surface, rho from the
// source): min 0 (`origin` says what 0 is), max a finite number > 0 in `unit` (the key that
// names the unit, e.g. "medium.length_unit"), and its bins.
void check_from_zero(const UniformAxis& axis, const std::string& name, const std::string& origin,
                     const std::string& unit);

}  // namespace scatterlab
