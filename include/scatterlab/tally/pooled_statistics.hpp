#pragma once
// Two independent sets of batch estimates of one cell, pooled as if they were one set: the mean
// over all batches and the sum of squared deviations about it (Chan, Golub & LeVeque 1979,
// "Updating formulae and a pairwise algorithm for computing sample variances", eq. 2.1):
//   n = n_a + n_b,  delta = mean_b - mean_a,
//   mean = mean_a + delta n_b / n,   M2 = M2_a + M2_b + delta^2 n_a n_b / n.
// The standard error of the pooled mean is then sqrt(M2 / (n (n - 1))) (batch_statistics.hpp).
// A run's file stores stderr, from which M2 = stderr^2 n (n - 1).

#include <cmath>

namespace scatterlab {

struct BatchSet {
  double mean = 0.0;
  double squares = 0.0;  // M2: sum of squared deviations of the batch estimates from the mean
  double batches = 0.0;

  static BatchSet from_standard_error(double mean, double standard_error, double batches) {
    return {mean, standard_error * standard_error * batches * (batches - 1.0), batches};
  }
  double standard_error() const { return std::sqrt(squares / (batches * (batches - 1.0))); }
};

inline BatchSet pool(const BatchSet& a, const BatchSet& b) {
  const double n = a.batches + b.batches;
  const double delta = b.mean - a.mean;
  return {a.mean + delta * (b.batches / n),
          a.squares + b.squares + delta * delta * (a.batches * b.batches / n), n};
}

}  // namespace scatterlab
