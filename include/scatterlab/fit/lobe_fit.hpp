#pragma once
// Fitting one lobe: the radiance of one spatial bin over all directions.
//
// Objective: chi-square on L, the quantity the tally measures. Direction i's residual is
//   r_i = (<m>_i - L_i) / sigma_i,
// with <m>_i the model averaged over angular bin i (lobe_grid.hpp), L_i the tally's batch mean
// and sigma_i its standard error. sum r_i^2 is the chi-square of the fit: for an exact model
// each r_i is a z-score, and chi^2 / dof is about 1 (dof = directions - free parameters).
// Every direction of the sphere takes part, dark ones included.
//
// Standard errors of dim directions. A batch standard error is estimated from the events that
// fell in the bin: a direction no photon reached has L = 0 and stderr = 0, and one that a few
// photons reached has an stderr as noisy as its mean. Neither may get an infinite weight, and
// neither may be dropped (dropping the dark directions lets a model put light where the tally
// saw none). Both are floored at the standard error of one event:
//   sigma_i = max(stderr_i, Q / Omega_i).
// For a tally of n events of radiance q each (one event adds q to the mean of its direction),
// L = n q and stderr^2 = n q^2, so q = stderr^2 / L; an event of a given weight adds
// q = (weight / batches) / Omega_i to a direction of solid angle Omega_i, so q Omega_i is the
// same in every direction of the lobe: Q is the median of stderr_i^2 Omega_i / L_i over the
// directions with L_i > 0. A dark direction then says "fewer than about one event here", which
// is what the tally knows. Where no direction has a standard error (noise-free data), sigma_i
// is 1e-6 of L_i (at least 1e-12 of the brightest L): every direction known to the same relative
// precision, as if counted with the same number of events; an exact model still fits to zero.
//
// Reported per bin, over all directions, from the same L, stderr and <m>:
//   error       relative L1 error over the sphere, sum Omega |<m> - L| / sum Omega L
//   error_plane the same over the bins on the phi = 0 / phi = pi plane (Vavassori Figs. 4.5, 4.8)
//   noise       sqrt(2/pi) sum Omega stderr / sum Omega L: the error an exact model would show
//               (the mean |x| of a normal deviate is sqrt(2/pi) sigma). It uses the tally's own
//               stderr, not the floor: an exact model is ~0 where the tally saw nothing.
//   chi2_dof    sum r_i^2 / (directions - free parameters)
//
// Why not log L: a fit in log L trades a relative error in a dark direction for the same
// relative error at the peak, so a free axis can overshoot the peak 40-fold for a better fit of
// the tail; the L1 error in L, which is what a renderer sees, then gets worse although the
// objective improves. Chi-square on L makes the objective and the reported error measure the
// same thing, and its weights are the tally's own.

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
  converged = 0,            // Ceres CONVERGENCE, finite, no parameter on an artificial bound
  iteration_limit = 1,      // Ceres NO_CONVERGENCE (iteration limit): parameters are usable
  solver_failure = 2,       // Ceres FAILURE or USER_FAILURE: not usable
  non_finite = 3,           // non-finite parameters or cost after the solve: not usable
  at_bound = 4,             // converged onto an artificial bound: usable, the optimum lies beyond
  estimate = 5,             // dexp_paper: the paper's four-step estimate, no solve: usable
  all_zero = 10,            // no radiance in any direction: skipped
  too_few_directions = 11,  // fewer resolved directions than FitOptions::min_directions: skipped
  non_finite_input = 12,    // NaN or infinite mean or stderr in the file: skipped
  no_axis = 13,             // sg only: vector irradiance E = 0 gives no axis: skipped
};

std::string to_string(FitStatus status);
std::string fit_status_legend();  // "0 converged; 1 iteration_limit; ..."
inline bool usable(FitStatus status) {
  return status == FitStatus::converged || status == FitStatus::iteration_limit ||
         status == FitStatus::at_bound || status == FitStatus::estimate;
}
inline bool skipped(FitStatus status) {
  return static_cast<std::int32_t>(status) >= 10;
}

// Artificial bounds (beyond any lobe of the simulations; a fit that ends on one is at_bound).
inline constexpr double kSharpnessBound = 1e5;  // SG lambda, ASG lambda and mu
inline constexpr double kGammaBound = 50.0;     // e^{50 sqrt 2}: far beyond any lobe, finite
inline constexpr double kEtaBound = 8.0;        // widths differ by e^{8/2} ~ 55 at most
inline constexpr double kRidgeGBound = 0.999;   // the ridge's |g| (a phase function needs < 1)

struct FitOptions {
  // A direction is resolved when L > 0 and stderr / L <= max_relative_stderr (about four events
  // or more); a lobe needs min_directions resolved directions to be fitted. All directions
  // enter the fit either way.
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

// What a fit sees of one lobe: every direction's L and sigma (see the top of this file).
struct LobeObservations {
  FitStatus status = FitStatus::converged;  // a skip status when the bin cannot be fitted
  std::string message;                      // why, for a skipped bin
  std::vector<double> radiance;             // L_i, all directions
  std::vector<double> stderr_of_mean;       // the tally's own
  std::vector<double> sigma;                // max(stderr_i, Q / Omega_i)
  double event_radiance = 0.0;              // Q: one event's L times its solid angle
  std::size_t resolved = 0;
};

LobeObservations observe(const LobeGrid& grid, const LobeData& data, const FitOptions& options);

struct LobeFit {
  FitStatus status = FitStatus::solver_failure;
  std::string message;  // empty when converged
  LobeParameters parameters;
  double cost = 0.0;  // 1/2 chi-square at the solution
  int iterations = 0;
  double error_sphere = -1.0;  // -1 where the bin was not fitted (never NaN)
  double error_plane = -1.0;
  double noise = -1.0;
  double chi2_dof = -1.0;
};

// Half the chi-square of `parameters`, in double (to choose among starts); infinity where the
// model is not finite.
double fit_cost(LobeModel model, const LobeGrid& grid, const LobeObservations& observations,
                const LobeParameters& parameters);

// Chi-square fit from `start` with Ceres (Levenberg-Marquardt, dense QR). The axis is held at
// start.axis for sg and moves on the sphere otherwise; bounds: lambda, mu in [0, 1e5],
// |gamma| <= 50, |eta| <= 8; for the ridge c >= 0, |g| <= 0.999, k in [0, 1e5],
// theta_on in [0, pi], w in [1e-3, 1], spread c >= 0, kappa in [0, 1e5]; adexp2_ridge's second
// lobe as adexp's, its axis on the sphere too. Fills the errors.
// `observations` must come from observe() and not be skipped. dexp_paper is not solved: its fit is
// the start, with status estimate.
LobeFit fit_lobe(LobeModel model, const LobeGrid& grid, const LobeData& data,
                 const LobeObservations& observations, const LobeParameters& start,
                 const FitOptions& options = {});

// Starting points computed from the data alone, in log L over the directions with L > 0, each
// weighted by (L / sigma)^2 (the delta method: the variance of log L is (sigma / L)^2).
// SG: weighted linear regression of log L on (p.w - 1) at the bin centres, for a given axis,
// or, where it fits better, lambda from a grid with mu at its chi-square optimum.
LobeParameters spherical_gaussian_estimate(const LobeGrid& grid,
                                           const LobeObservations& observations,
                                           const Eigen::Vector3d& axis);
// Vavassori §4.2.2's four steps: p and M from the peak bin; gamma from the mean log L on the
// rings p.w = 3/4 and p.w = 0; log alpha by linear regression; beta = log M - log alpha.
LobeParameters double_exponential_estimate(const LobeGrid& grid,
                                           const LobeObservations& observations);
// ASG from an SG: near the axis 1 - v.p = (1 - (v.p)^2) / (1 + v.p) ~ ((v.x)^2 + (v.y)^2) / 2,
// so exp(lambda (v.p - 1)) ~ exp(-lambda/2 ((v.x)^2 + (v.y)^2)): lambda_asg = mu_asg = lambda / 2,
// c = the SG's amplitude.
LobeParameters asg_from_sg(const LobeParameters& sg);
// adexp_ridge from an adexp solution. `with_ridge = false`: c = 0, which is adexp exactly.
// Otherwise the ridge's onset is put just before the bin on the line where the tally lies most
// standard errors above the adexp, and c is the weighted least-squares amplitude of the
// excess on the line (0 where there is none).
LobeParameters ridge_from_adexp(const LobeGrid& grid, const LobeObservations& observations,
                                const LobeParameters& adexp, bool with_ridge);

// adexp2_ridge from an adexp_ridge solution, two starts: the second lobe of half the first's
// height and slope, tilted 0.3 rad towards e_r, where the forward light beside the beam lies;
// and the same lobe e^{-30} as bright as the first (adexp_ridge to within e^{-30}: a start no
// worse than the subset's solution), first.
std::vector<LobeParameters> second_lobe_starts(const LobeParameters& ridge);

// Relative L1 errors (sphere, plane), the noise level and chi^2 / dof (see the top of this
// file); -1 where undefined.
struct LobeErrors {
  double sphere = -1.0;
  double plane = -1.0;
  double noise = -1.0;
  double chi2_dof = -1.0;
};
LobeErrors lobe_errors(LobeModel model, const LobeGrid& grid, const LobeObservations& observations,
                       const LobeParameters& parameters);

// log of the model averaged over angular bin `bin`.
double log_bin_average(LobeModel model, const LobeGrid& grid, std::size_t bin,
                       const LobeParameters& parameters);

}  // namespace scatterlab::fit
