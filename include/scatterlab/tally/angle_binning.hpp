#pragma once
// Bins an angle given only its cosine, without acos or atan2 in the hot loop.
//
// The angle axis [0, A] with A <= pi is uniform in angle, so its edges are not uniform in
// cosine. A table over cosine cells gives the first candidate bin; exact comparisons with the
// edge cosines then finish the job, so the bin is the same one acos would give, up to the
// rounding of the edge cosines themselves.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "scatterlab/tally/axis.hpp"

namespace scatterlab {

class CosineBinning {
 public:
  CosineBinning() = default;

  explicit CosineBinning(const UniformAxis& angle) : bins_(angle.bins) {
    edge_cosines_.resize(static_cast<std::size_t>(bins_) + 1);
    for (int k = 0; k <= bins_; ++k)
      edge_cosines_[static_cast<std::size_t>(k)] = std::cos(angle.edge(k));
    // Cells narrower than the closest pair of edge cosines hold at most one edge each, so the
    // loop in bin() runs at most once; very fine grids cap the table and loop a little more.
    double narrowest = 2.0;
    for (int k = 0; k < bins_; ++k) {
      narrowest = std::min(narrowest, edge_cosines_[static_cast<std::size_t>(k)] -
                                          edge_cosines_[static_cast<std::size_t>(k) + 1]);
    }
    const double wanted = std::ceil(4.0 / std::max(narrowest, 1e-12));
    cells_ = static_cast<int>(std::clamp(wanted, 64.0, 65536.0));
    cell_scale_ = cells_ / 2.0;
    first_bin_.resize(static_cast<std::size_t>(cells_) + 1);
    for (int j = 0; j <= cells_; ++j) {
      // The largest cosine of cell j is its top end, 1 - j / cell_scale.
      const double top = 1.0 - j / cell_scale_;
      first_bin_[static_cast<std::size_t>(j)] = static_cast<std::uint32_t>(slow_bin(top));
    }
  }

  // The bin of the angle whose cosine is `cosine`; cosines below cos(A) give the last bin.
  [[gnu::always_inline]] int bin(double cosine) const {
    const double u = std::clamp((1.0 - cosine) * cell_scale_, 0.0, static_cast<double>(cells_));
    int k = first_bin_[static_cast<std::size_t>(u)];
    while (k + 1 < bins_ && cosine < edge_cosines_[static_cast<std::size_t>(k) + 1]) ++k;
    return k;
  }

  const std::vector<double>& edge_cosines() const { return edge_cosines_; }

 private:
  int slow_bin(double cosine) const {
    int k = 0;
    while (k + 1 < bins_ && cosine < edge_cosines_[static_cast<std::size_t>(k) + 1]) ++k;
    return k;
  }

  int bins_ = 1;
  int cells_ = 64;
  double cell_scale_ = 32.0;
  std::vector<double> edge_cosines_;
  std::vector<std::uint32_t> first_bin_;
};

}  // namespace scatterlab
