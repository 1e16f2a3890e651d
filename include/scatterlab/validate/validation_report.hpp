#pragma once
// Writes the comparisons as CSV tables and PNG figures into a directory (created if missing;
// every file written atomically), and formats the error table for the terminal.

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/validate/half_space_comparison.hpp"
#include "scatterlab/validate/point_source_comparison.hpp"

namespace scatterlab {

// deon_point_source.csv (every shell of every albedo), deon_errors.csv (the error table) and,
// per albedo, deon_albedo_<c>_linear.png and _log.png of rho^2 phi(rho). Returns the paths.
std::vector<std::filesystem::path> write_point_source_report(
    const std::vector<PointSourceComparison>& comparisons, const std::filesystem::path& directory);

// The error table: one row per albedo, near and far mean relative errors of each model, and the
// Monte Carlo's agreement with the exact solution in its own standard errors.
std::string point_source_error_table(const std::vector<PointSourceComparison>& comparisons);

// <stem>_reflectance.csv and the pencil plots <stem>_reflectance_{linear,log,sqrt,rR}.png
// (Bitterli §3.6.3), plus <stem>_fluence.csv and <stem>_fluence_axis.png (phi along z in the
// innermost r bin). Returns the paths.
std::vector<std::filesystem::path> write_half_space_report(const HalfSpaceComparison& comparison,
                                                           const std::filesystem::path& directory,
                                                           const std::string& stem);

}  // namespace scatterlab
