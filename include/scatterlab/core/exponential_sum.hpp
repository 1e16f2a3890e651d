#pragma once
// sum_k w_k exp(-x c_k) with many terms, in vector lanes chosen at run time (Highway): a
// quadrature rule over exponentials (an escape probability over exit cosines, say) evaluated at
// every node of an outer integral.

#include <span>
#include <vector>

namespace scatterlab {

class ExponentialSum {
 public:
  // Weights w_k and rates c_k >= 0, as many of each.
  ExponentialSum(std::span<const double> weights, std::span<const double> rates);
  ExponentialSum() = default;

  // For x >= 0 (a term whose exponent is below -1000 is 0, as exp underflows). Highway's exp is
  // within 1 ulp of e^x; the lanes' partial sums are added as a tree, so the last bits depend on
  // the instruction set's lane count.
  double operator()(double x) const;

 private:
  // Padded with zero weights to a multiple of every target's lanes.
  std::vector<double> weights_, rates_;
};

}  // namespace scatterlab
