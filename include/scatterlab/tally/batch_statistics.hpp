#pragma once
// Batch statistics (as in OpenMC): each batch gives an independent estimate x_b of every
// tally cell; the result is their mean and the standard error of that mean,
//   stderr = sqrt( sum_b (x_b - mean)^2 / (B (B - 1)) ).
// Batches are added with Welford's update, in batch order, so that the result is the same
// whatever order the batches finished in.
//
// A block of cells that no batch has scored yet holds mean 0 and sum of squares 0, which a batch
// of zeros leaves exactly as they are (delta = 0 - 0, mean += 0, squares += 0 * 0): such a block
// is skipped while the batch's sums there are zero, so that a short batch on a large grid costs a
// read of its buffer rather than a Welford update of every cell. Same bits as folding every cell.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace scatterlab {

class BatchStatistics {
 public:
  // Cells per block of the untouched test. Calls on disjoint ranges whose bounds are multiples
  // of it may run on different threads at once.
  static constexpr std::size_t kBlock = 64;

  explicit BatchStatistics(std::size_t cells)
      : mean_(cells, 0.0), squares_(cells, 0.0), untouched_(blocks(cells), 1) {}
  // Continues from a saved state (a checkpoint): the Welford mean and sum of squares per cell,
  // every block counted as scored.
  BatchStatistics(std::vector<double> mean, std::vector<double> squares)
      : mean_(std::move(mean)), squares_(std::move(squares)), untouched_(blocks(mean_.size()), 0) {}

  // Adds x_b = batch_sums / photons_in_batch for cells [begin, end) and clears batch_sums
  // there. Call once per batch for every cell range, with batch_index counting from 0 in order.
  void add_batch(std::size_t batch_index, double* batch_sums, double photons_in_batch,
                 std::size_t begin, std::size_t end) {
    const double per_photon = 1.0 / photons_in_batch;
    const double weight = 1.0 / static_cast<double>(batch_index + 1);
    for (std::size_t first = begin; first < end;) {
      const std::size_t block = first / kBlock;
      const std::size_t last = std::min(end, (block + 1) * kBlock);
      if (untouched_[block] != 0 && all_zero(batch_sums + first, batch_sums + last)) {
        first = last;
        continue;
      }
      untouched_[block] = 0;
      for (std::size_t i = first; i < last; ++i) {
        const double x = batch_sums[i] * per_photon;
        batch_sums[i] = 0.0;
        const double delta = x - mean_[i];
        mean_[i] += delta * weight;
        squares_[i] += delta * (x - mean_[i]);
      }
      first = last;
    }
  }

  std::size_t size() const { return mean_.size(); }
  const std::vector<double>& mean() const { return mean_; }
  const std::vector<double>& squares() const { return squares_; }

  std::vector<double> standard_error(std::size_t batches) const {
    return standard_error_from_squares(squares_, batches);
  }

  // NaN for fewer than two batches: one batch says nothing about the spread.
  static std::vector<double> standard_error_from_squares(const std::vector<double>& squares,
                                                         std::size_t batches) {
    std::vector<double> error(squares.size(), std::numeric_limits<double>::quiet_NaN());
    if (batches < 2) return error;
    const double scale = 1.0 / (static_cast<double>(batches) * static_cast<double>(batches - 1));
    for (std::size_t i = 0; i < error.size(); ++i) error[i] = std::sqrt(squares[i] * scale);
    return error;
  }

 private:
  static std::size_t blocks(std::size_t cells) { return (cells + kBlock - 1) / kBlock; }
  // Whether every value is +0 or -0: the bits but the sign, ORed, which vectorises.
  static bool all_zero(const double* first, const double* last) {
    std::uint64_t bits = 0;
    for (const double* x = first; x != last; ++x) bits |= std::bit_cast<std::uint64_t>(*x);
    return (bits << 1) == 0;
  }

  std::vector<double> mean_;
  std::vector<double> squares_;          // Welford's running sum of squared deviations
  std::vector<std::uint8_t> untouched_;  // per block: no batch has scored any of its cells yet
};

}  // namespace scatterlab
