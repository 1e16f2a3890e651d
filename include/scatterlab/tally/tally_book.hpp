#pragma once
// Where each declared tally lives in one flat buffer of per-photon sums, and how the batch
// means of those sums become the finished tallies (tally_result.hpp).
//
// Buffer: [all orders][unscattered][once scattered][multiply scattered][the rest]. The per-order
// blocks exist only when the run splits by scattering order; a block holds every tally declared
// by_order, in declaration order. Each score goes to the all-orders block and, when split, to
// its order's block too, so that every total carries its own batch variance instead of being a
// sum of correlated parts. The tallies not split by order follow the blocks.

#include <cstddef>
#include <initializer_list>
#include <vector>

#include "scatterlab/tally/tally_declaration.hpp"
#include "scatterlab/tally/tally_result.hpp"

namespace scatterlab {

class TallyBook {
 public:
  static constexpr std::size_t absent = static_cast<std::size_t>(-1);

  TallyBook(std::vector<TallyDeclaration> declarations, bool split_by_order);

  // Offset of the cells of the tally (not chained) of `score` whose filters bin along
  // `coordinates`, in order, in the all-orders block (or after the blocks), or absent: the
  // Scorer's fixed path for that pair looks it up here once.
  std::size_t offset(Score score, std::initializer_list<Coordinate> coordinates = {}) const;
  bool has(Score score, std::initializer_list<Coordinate> coordinates = {}) const {
    return offset(score, coordinates) != absent;
  }
  // Offset of declaration i's cells; a chained tally's is found only here.
  std::size_t offset_of(std::size_t i) const { return declaration_offsets_[i]; }
  // Whether any tally is chained (TallyDeclaration::chained): the walk then keeps time.
  bool has_chain() const;
  // Whether anything is scored in the volume (at collisions or along flights).
  bool scores_volume() const;

  bool split_by_order() const { return split_by_order_; }
  // Offset of the block of light scattered `order` times (0, 1, or 2 meaning two or more),
  // relative to the all-orders block; only meaningful when split by order.
  std::size_t order_block(int order) const {
    return (1 + static_cast<std::size_t>(order < 2 ? order : 2)) * block_size_;
  }
  std::size_t size() const { return size_; }
  const std::vector<TallyDeclaration>& declarations() const { return declarations_; }

  // The finished tallies from the batch mean and standard error of the raw sums per photon:
  // cell i of a tally is raw / (product of its filters' measures) x scale, where scale is the
  // power each photon carries (1, or the power that entered through a surface), in `length`'s
  // unit (its factor for the tally's units). Order: the by-order tallies block by block (all
  // orders, then _unscattered, _single, _multiple when split), then the rest, each group in
  // declaration order.
  std::vector<TallyResult> finish(const std::vector<double>& raw_mean,
                                  const std::vector<double>& raw_stderr, double scale,
                                  const ReportedLength& length = {}) const;

 private:
  std::vector<TallyDeclaration> declarations_;
  std::vector<std::size_t> declaration_offsets_;
  bool split_by_order_ = false;
  std::size_t block_size_ = 0;
  std::size_t size_ = 0;
};

}  // namespace scatterlab
