#pragma once
// A finished tally as it goes to the file: a named array with its dimensions, units, the batch
// mean and the standard error of that mean (DESIGN.md, HDF5 layout: /tallies/<name>/{mean,stderr}).

#include <cstddef>
#include <string>
#include <vector>

namespace scatterlab {

struct TallyResult {
  std::string name;                // e.g. "fluence", "radiance_single", "absorbed"
  std::vector<std::string> dims;   // grid axis per dimension, e.g. {"r", "z"}; empty for scalars
  std::vector<std::size_t> shape;  // extent per dimension, row-major; empty for scalars
  std::string units;               // e.g. "W mfp^-2 per W incident"
  std::string description;         // one line: what it is and which estimator made it
  std::vector<double> mean;        // product(shape) values (1 for a scalar)
  std::vector<double> stderr_of_mean;

  std::size_t size() const { return mean.size(); }
};

}  // namespace scatterlab
