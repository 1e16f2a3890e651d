#pragma once
// The figure of merit of a Monte Carlo estimate, FOM = 1 / (R^2 T), with R the relative standard
// error and T the run's time (X-5 Monte Carlo Team, MCNP - A General Monte Carlo N-Particle
// Transport Code, Version 5, Vol. I, LA-UR-03-1987, 2003, ch. 2 §VI.D "The Figure of Merit").
// R^2 falls as 1/N and T grows as N, so the FOM is a property of the method, not of the run's
// length: of two estimators of the same quantity (collision and track length), the one with the
// larger FOM reaches a given error sooner.

#include <span>

namespace scatterlab {

// stderr / |mean| for a scalar; for a binned tally the median of it over the bins whose mean is
// not 0, so that one figure stands for the whole grid. NaN when every mean is 0.
double relative_standard_error(std::span<const double> mean,
                               std::span<const double> stderr_of_mean);

// 1 / (R^2 T) in 1/s; NaN where it is not defined (R 0 or NaN, T not > 0).
double figure_of_merit(double relative_error, double seconds);

}  // namespace scatterlab
