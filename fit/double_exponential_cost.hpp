#pragma once
// The chi-square residuals of the double-exponential family (dexp, adexp, adexp_ridge;
// lobe_fit.hpp) with their Jacobian written out by the chain rule instead of carried through
// every node in Ceres Jets: the fits spend nearly all their time here.
//
// A node direction w enters the smooth lobe only through three projections and five numbers:
//   u = t1.w, v = t2.w, rho = 1 - p.w          (t1, t2 the symmetry tangents of p)
//   S = A u^2 + B v^2 + rho^2 / 2,  A = e^{eta} / 2,  B = e^{-eta} / 2,  s = sqrt(S)
//   l = a + b R(gamma, s),  R = (e^{gamma s} - 1) / gamma        (lobe_model.hpp, adexp)
// so its gradient with respect to the fourteen intermediates theta = (a, b, gamma, A, B, t1, t2,
// p) is, in doubles,
//   dl/da = 1, dl/db = R, dl/dgamma = b dR/dgamma, and through g = b e^{gamma s} / (2 s):
//   dl/dA = g u^2, dl/dB = g v^2, dl/dt1 = 2 g A u w, dl/dt2 = 2 g B v w, dl/dp = -g rho w
// (g = 0 at s = 0, the subgradient of lobe_model.hpp). A bin's average m = sum_q w_q e^{l_q}
// has dm/dtheta = sum_q w_q e^{l_q} dl_q/dtheta, and theta depends on the parameters (p, a, b,
// gamma, eta) through one 14 x 7 Jacobian per evaluation: dA/deta = A, dB/deta = -B, and
// dt1/dp, dt2/dp from Jets of width 3. The ridge (adexp_ridge) touches 2 of 36 columns of bins
// and a product of row and column averages; it is evaluated in Jets over (a, ridge).
//
// adexp2_ridge adds a second adexp of its own parameters, whose average over a bin is the same
// sum with the same gradient.
//
// dexp is adexp without eta, that is at eta = 0 (there S = |w - p|^2 / 2 for unit p: the same
// lobe as lobe_model.hpp's DoubleExponential).

#include <ceres/cost_function.h>

#include "lobe_bin_average.hpp"
#include "scatterlab/fit/lobe_fit.hpp"
#include "scatterlab/fit/lobe_grid.hpp"
#include "scatterlab/fit/lobe_model.hpp"

namespace scatterlab::fit {

// Parameter blocks: axis (3), shape (a, b, gamma) for dexp and (a, b, gamma, eta) for adexp
// and the ridge models, for adexp_ridge and adexp2_ridge the ridge (7), and for adexp2_ridge the
// second lobe's axis (3) and shape (4).
class DoubleExponentialCost final : public ceres::CostFunction {
 public:
  // The models it serves: dexp (and dexp_paper), adexp, adexp_ridge and adexp2_ridge.
  static bool serves(LobeModel model) {
    return model == LobeModel::dexp_paper || model == LobeModel::dexp ||
           model == LobeModel::adexp || model == LobeModel::adexp_ridge ||
           model == LobeModel::adexp2_ridge;
  }

  // Throws std::invalid_argument for a model it does not serve.
  DoubleExponentialCost(const LobeGrid& grid, const LobeObservations& observations,
                        LobeModel model);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const LobeGrid& grid_;
  BinNodes nodes_;  // the grid's nodes as the vector loop reads them
  const LobeObservations& observations_;
  int shape_size_;
  bool with_ridge_;
  bool two_lobes_;
};

}  // namespace scatterlab::fit
