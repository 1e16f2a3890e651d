#pragma once
// A finished tally as it goes to the file: a named array with its dimensions, units, the batch
// mean and the standard error of that mean (in the file: /tallies/<name>/{mean,stderr}).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace scatterlab {

// An axis a tally brings itself (a declared tally's filter, in the scene's units), which stands
// in for /grid/<dim> (in the file: /tallies/<name>/axes/<dim>, its bin edges with their units).
struct TallyAxis {
  std::string dim;
  std::vector<double> edges;
  std::string units;
};

struct TallyResult {
  std::string name;                // e.g. "fluence", "radiance_single", "absorbed"
  std::vector<std::string> dims;   // grid axis per dimension, e.g. {"r", "z"}; empty for scalars
  std::vector<std::size_t> shape;  // extent per dimension, row-major; empty for scalars
  std::string units;               // e.g. "W mfp^-2 per W incident"
  std::string description;         // one line: what it is and which estimator made it
  std::vector<double> mean;        // product(shape) values (1 for a scalar)
  std::vector<double> stderr_of_mean;
  std::vector<TallyAxis> axes = {};  // its own axes, where it has them

  std::size_t size() const { return mean.size(); }
};

// The tally called `name` among `tallies`, or nullptr when there is none.
inline const TallyResult* find_tally(const std::vector<TallyResult>& tallies,
                                     std::string_view name) {
  for (const TallyResult& t : tallies) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

// Fills `tally` (name, dims, shape, units and description set) from the raw per-photon batch
// mean and standard error at [offset, offset + cells), dividing cell i by measure(i): its
// volume, area or solid angle, as the tally's units ask.
template <class Measure>
TallyResult measured_tally(TallyResult tally, const std::vector<double>& raw_mean,
                           const std::vector<double>& raw_stderr, std::size_t offset,
                           Measure&& measure) {
  std::size_t cells = 1;
  for (std::size_t extent : tally.shape) cells *= extent;
  tally.mean.resize(cells);
  tally.stderr_of_mean.resize(cells);
  for (std::size_t i = 0; i < cells; ++i) {
    const double m = measure(i);
    tally.mean[i] = raw_mean[offset + i] / m;
    tally.stderr_of_mean[i] = raw_stderr[offset + i] / m;
  }
  return tally;
}

}  // namespace scatterlab
