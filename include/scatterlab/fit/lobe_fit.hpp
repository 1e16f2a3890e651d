#pragma once
// Fitting one lobe: the radiance of one spatial bin over all directions.
//
// Fit space. The residuals are in log L:
//   r_i = w_i (log <m>_i - log L_i),   w_i = sqrt(Omega_i / Omega_mean) / sqrt(s_i^2 + f^2),
// with <m>_i the model averaged over angular bin i (lobe_grid.hpp), s_i = stderr_i / L_i the
// tally's relative standard error, f a floor on it, and Omega_i the bin's solid angle.
//   - log L: a g = 0.9 lobe spans four to six decades between its peak and its back; in L
//     itself the fit sees the peak alone and the "diffuse" part that separates the models
//     (Vavassori §4.2.1, Fig. 4.7) weighs nothing. Vavassori builds the double exponential in
//     log L too (§4.2.2, Fig. 4.8). A residual in log L is a relative error.
//   - stderr: the standard error of log L is stderr / L (delta method), so r_i is a z-score.
//     The floor f (1 % by default) keeps the few bins with 1e-3 relative errors from deciding
//     the whole fit of a model that cannot be exact anywhere.
//   - solid angle: equal-angle bins crowd near the poles; weighting by Omega_i makes the sum
//     over bins an integral over the sphere.
// Directions with zero or non-finite radiance, or relative stderr above max_relative_stderr
// (fewer than a handful of batches saw them), are left out of the fit.
//
// The reported errors are relative L1 errors of the bin-averaged model over the directions the
// fit used: sum Omega |<m> - L| / sum Omega L, over the sphere and over the bins on the
// phi = 0 / phi = pi plane. Directions the tally does not resolve are left out here too: at
// 1e8 photons most backward directions of an off-axis bin hold zero or one batch's worth of
// radiance, and comparing a model with that measures the photon count, not the model. Beside
// them, noise = sqrt(2/pi) sum Omega stderr / sum Omega L is the error an exact model would
// show on these data (the mean |x| of a normal deviate is sqrt(2/pi) sigma).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "scatterlab/fit/lobe_grid.hpp"
#include "scatterlab/fit/lobe_model.hpp"

namespace scatterlab::fit {

// Stored as int32 in /fits/<model>/status; fit_status_legend() spells them out.
enum class FitStatus : std::int32_t {
  converged = 0,           // Ceres CONVERGENCE
  no_convergence = 1,      // Ceres NO_CONVERGENCE (iteration limit): parameters are usable
  failed = 2,              // Ceres FAILURE, or a non-finite result
  all_zero = 10,           // no radiance in any direction: skipped
  too_few_directions = 11, // fewer usable directions than FitOptions::min_directions: skipped
  non_finite_input = 12,   // NaN or infinite mean or stderr in the file: skipped
  no_axis = 13,            // sg only: vector irradiance E = 0 gives no axis: skipped
};

std::string to_string(FitStatus status);
std::string fit_status_legend();  // "0 converged; 1 no_convergence; ..."
inline bool usable(FitStatus status) {
  return status == FitStatus::converged || status == FitStatus::no_convergence;
}

struct FitOptions {
  double relative_stderr_floor = 0.01;
  double max_relative_stderr = 0.5;
  std::size_t min_directions = 10;
  int max_iterations = 200;
};

// One spatial bin's data: grid.size() values each, and the vector irradiance in the local frame.
struct LobeData {
  std::span<const double> mean;
  std::span<const double> stderr_of_mean;
  Eigen::Vector3d flux = Eigen::Vector3d::Zero();  // (E_r, 0, E_z)
};

// The directions a fit uses, with log L and the weights above.
struct LobeObservations {
  FitStatus status = FitStatus::converged;  // a skip status when the bin cannot be fitted
  std::string message;                      // why, for a skipped bin
  std::vector<std::size_t> bins;
  std::vector<double> log_radiance;
  std::vector<double> weights;
};

LobeObservations observe(const LobeGrid& grid, const LobeData& data, const FitOptions& options);

struct LobeFit {
  FitStatus status = FitStatus::failed;
  std::string message;  // empty when converged
  LobeParameters parameters;
  double cost = 0.0;     // 1/2 sum r_i^2 at the solution
  int iterations = 0;
  double error_sphere = -1.0;  // -1 where the bin was not fitted (never NaN)
  double error_plane = -1.0;
  double noise = -1.0;
};

// Half the sum of squared residuals of `parameters`, in double (to choose among starts).
double fit_cost(LobeModel model, const LobeGrid& grid, const LobeObservations& observations,
                const LobeParameters& parameters);

// Least squares from `start` with Ceres (Levenberg-Marquardt, dense QR). The axis is held at
// start.axis for sg and moves on the sphere otherwise; lambda >= 0, |gamma| <= 50, |eta| <= 8.
// Fills the errors from `data`. `observations` must come from observe() and not be skipped.
LobeFit fit_lobe(LobeModel model, const LobeGrid& grid, const LobeData& data,
                 const LobeObservations& observations, const LobeParameters& start,
                 const FitOptions& options = {});

// Starting points computed from the data alone.
// SG: weighted linear regression of log L on (p.w - 1) at the bin centres, for a given axis.
LobeParameters spherical_gaussian_estimate(const LobeGrid& grid,
                                           const LobeObservations& observations,
                                           const Eigen::Vector3d& axis);
// Vavassori §4.2.2's four steps: p and M from the peak bin; gamma from the mean log L on the
// rings p.w = 3/4 and p.w = 0; log alpha by linear regression; beta = log M - log alpha.
// adexp starts from it with eta = 0.
LobeParameters double_exponential_estimate(const LobeGrid& grid,
                                           const LobeObservations& observations);

// Relative L1 errors (sphere, plane) of the bin-averaged model against the data over the
// observed directions, and the noise level (see the top of this file); -1 where undefined.
struct LobeErrors {
  double sphere = -1.0;
  double plane = -1.0;
  double noise = -1.0;
};
LobeErrors lobe_errors(LobeModel model, const LobeGrid& grid, const LobeData& data,
                       const LobeObservations& observations, const LobeParameters& parameters);

// log of the model averaged over angular bin `bin`.
double log_bin_average(LobeModel model, const LobeGrid& grid, std::size_t bin,
                       const LobeParameters& parameters);

}  // namespace scatterlab::fit
