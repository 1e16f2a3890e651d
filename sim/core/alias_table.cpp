#include "scatterlab/core/alias_table.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

namespace scatterlab {

AliasTable::AliasTable(const std::vector<double>& weights) {
  const std::size_t n = weights.size();
  if (n == 0 || n > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("AliasTable: between 1 and 2^32 - 1 weights are accepted");
  }
  double total = 0.0;
  for (const double w : weights) {
    if (!std::isfinite(w) || w < 0.0) {
      throw std::invalid_argument("AliasTable: weights must be finite and >= 0");
    }
    total += w;
  }
  if (!(total > 0.0) || !std::isfinite(total)) {
    throw std::invalid_argument("AliasTable: some weight must be > 0, and their sum finite");
  }
  // Vose §3: each column's share scaled to mean 1; a column under 1 is topped up from one over.
  columns_.resize(n);
  std::vector<double> share(n);
  std::vector<std::uint32_t> small, large;
  for (std::size_t i = 0; i < n; ++i) {
    share[i] = weights[i] * static_cast<double>(n) / total;
    columns_[i].self = static_cast<std::uint32_t>(i);
    (share[i] < 1.0 ? small : large).push_back(static_cast<std::uint32_t>(i));
  }
  while (!small.empty() && !large.empty()) {
    const std::uint32_t under = small.back(), over = large.back();
    small.pop_back();
    columns_[under].keep = share[under];
    columns_[under].alias = over;
    share[over] -= 1.0 - share[under];
    if (share[over] < 1.0) {
      large.pop_back();
      small.push_back(over);
    }
  }
  // What is left is 1 but for rounding: kept whole.
  for (const std::uint32_t i : large) columns_[i].keep = 1.0;
  for (const std::uint32_t i : small) columns_[i].keep = 1.0;
}

}  // namespace scatterlab
