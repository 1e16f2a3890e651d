#pragma once
// The smooth lobe of the double-exponential family (double_exponential_cost.hpp) averaged over
// every angular bin at once, with each average's gradient in the lobe's intermediates: the loop
// the fits spend most of their time in, in Highway vectors whose lanes are bins (the nodes are
// stored slot-major, node q of every bin side by side), compiled for each instruction set and
// chosen at run time.

#include <array>
#include <cstddef>
#include <vector>

#include "scatterlab/fit/lobe_grid.hpp"

namespace scatterlab::fit {

// A lobe's numbers that every node uses: l(w) = a + b R(gamma, s(w)) with
// s^2 = A (t1.w)^2 + B (t2.w)^2 + (1 - p.w)^2 / 2 (double_exponential_cost.hpp).
struct LobeTerms {
  std::array<double, 3> axis, t1, t2;
  double a, b, gamma, along_scale, across_scale;  // A and B
};

// The grid's quadrature nodes, slot-major: direction and weight of node q of bin i at
// q * padded_bins + i. Bins are padded to a multiple of the widest vector any target may have
// (32 doubles) with nodes of weight 0, whose averages nobody reads.
struct BinNodes {
  explicit BinNodes(const LobeGrid& grid);
  std::size_t bins = 0, padded_bins = 0, slots = 0;
  std::vector<double> x, y, z, weight;
};

// Per bin i: m_i = sum_q w_q e^{l_q} = scale[i] sum[i] with scale = e^{largest}, largest the
// largest l_q of the bin (so that neither overflows), and the gradient of sum[i] in
// (b, gamma, A, B, t1, t2, p), the header's order: ramp = sum_q w'_q R_q,
// ramp_gamma = sum_q w'_q b dR/dgamma, along and across = sum_q g_q u_q^2 and g_q v_q^2,
// d_t1[k] = sum_q 2 g_q A u_q w_k, d_t2[k] likewise with B and v, d_p[k] = -sum_q g_q rho_q w_k,
// where w'_q = w_q e^{l_q - largest} and g_q = w'_q b e^{gamma s_q} / (2 s_q).
struct BinAverages {
  std::vector<double> scale, sum, ramp, ramp_gamma, along, across;
  std::array<std::vector<double>, 3> d_t1, d_t2, d_p;
};

// Fills `out` (resized to nodes.padded_bins; without the Jacobian only scale and sum).
void average_over_bins(const LobeTerms& lobe, const BinNodes& nodes, bool want_jacobian,
                       BinAverages& out);

}  // namespace scatterlab::fit
