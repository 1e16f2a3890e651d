#pragma once
// Draws an index with probability proportional to its weight in constant time: Walker's alias
// method (Walker 1977, "An efficient method for generating discrete random variables with
// general distributions", ACM TOMS 3(3)), built as Vose 1991 ("A linear algorithm for generating
// random numbers with a given distribution", IEEE TSE 17(9), §3) builds it, which keeps the
// columns' probabilities in [0, 1] however the weights round.
//
// Column i of n keeps i with probability keep[i] and otherwise gives alias[i]; one uniform u
// picks the column (floor(u n)) and, from its fraction, the coin.

#include <cstdint>
#include <vector>

namespace scatterlab {

class AliasTable {
 public:
  // Throws std::invalid_argument unless every weight is finite and >= 0 and some is > 0, and
  // there are fewer than 2^32.
  explicit AliasTable(const std::vector<double>& weights);

  // The index for a uniform u in [0, 1).
  std::uint32_t draw(double u) const {
    const double x = u * static_cast<double>(columns_.size());
    const auto i = static_cast<std::size_t>(x);
    const Column& column = columns_[i < columns_.size() ? i : columns_.size() - 1];
    return x - static_cast<double>(i) < column.keep ? column.self : column.alias;
  }

  std::size_t size() const { return columns_.size(); }

 private:
  struct Column {
    double keep = 1.0;
    std::uint32_t self = 0, alias = 0;
  };
  std::vector<Column> columns_;
};

}  // namespace scatterlab
