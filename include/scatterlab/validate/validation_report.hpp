#pragma once
// Writes the comparisons as CSV tables and PNG figures into a directory (created if missing;
// every file written atomically), and formats the error table for the terminal.

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/validate/half_space_comparison.hpp"
#include "scatterlab/validate/lit_sphere_comparison.hpp"
#include "scatterlab/validate/point_source_comparison.hpp"

namespace scatterlab {

// deon_point_source.csv (every shell of every albedo), deon_errors.csv (the error table) and,
// per albedo, deon_albedo_<c>_linear.png and _log.png of rho^2 phi(rho). Returns the paths.
std::vector<std::filesystem::path> write_point_source_report(
    const std::vector<PointSourceComparison>& comparisons, const std::filesystem::path& directory);

// The error table: one row per albedo, near and far mean relative errors of each model, and the
// Monte Carlo's agreement with the exact solution in its own standard errors.
std::string point_source_error_table(const std::vector<PointSourceComparison>& comparisons);

// <stem>_reflectance.csv (every Monte Carlo part and every model, named with the part it models)
// and the pencil plots <stem>_reflectance_{multiple,all}_{linear,log,sqrt,rR}.png (Bitterli
// §3.6.3), each model beside the Monte Carlo part it models; plus <stem>_fluence.csv and
// <stem>_fluence_axis_{multiple,all}.png (phi along z in the innermost r bin). Returns the paths.
std::vector<std::filesystem::path> write_half_space_report(const HalfSpaceComparison& comparison,
                                                           const std::filesystem::path& directory,
                                                           const std::string& stem);

// The once-scattered R_1(r) of Monte Carlo (reflectance_single) against the exact refractive
// single-scatter solution, ring by ring, in Monte Carlo standard errors.
struct SingleScatterAgreement {
  std::size_t rings = 0;        // rings compared: Monte Carlo resolved (mean > 3 stderr)
  double max_abs_z = 0.0;       // largest |MC - exact| / stderr
  double mean_squared_z = 0.0;  // ~1 when the two agree
  double total_z = 0.0;         // of the totals, (MC - exact) / stderr
};

SingleScatterAgreement compare_single_scatter(const MonteCarloCurve& monte_carlo,
                                              const SingleScatterReflectance& exact,
                                              double monte_carlo_total,
                                              double monte_carlo_total_stderr);

// <stem>_single_scatter.csv (r, MC, stderr, exact, its quadrature error, z) and
// <stem>_single_scatter_log.png, whose title gives the medium. Returns the paths.
std::vector<std::filesystem::path> write_single_scatter_report(
    const std::vector<double>& r_edges, const MonteCarloCurve& monte_carlo,
    const SingleScatterReflectance& exact, const HalfSpaceMedium& medium,
    const std::filesystem::path& directory, const std::string& stem);

// litsphere_exitance.csv (M(psi) of every case: Monte Carlo all orders and multiply scattered,
// each model, with standard errors), litsphere_errors.csv (the region errors) and one log plot
// per case, litsphere_<slug>.png. Returns the paths.
std::vector<std::filesystem::path> write_lit_sphere_report(
    const std::vector<LitSphereComparison>& comparisons, const std::filesystem::path& directory);

// One row per case and model: mean relative error on the lit side, at the terminator and on
// the shadow side (lit_sphere_comparison.hpp).
std::string lit_sphere_error_table(const std::vector<LitSphereComparison>& comparisons);

}  // namespace scatterlab
