#pragma once
// What a mistyped name was meant to be: scene keys, material names and command-line flags all
// suggest the accepted name nearest to what was typed ("did you mean").

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace scatterlab {

// Levenshtein distance: the fewest insertions, deletions and substitutions from a to b.
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The accepted name nearest to `typed`, when it is within one edit per three characters
// ("albdo" -> "albedo", "--photon" -> "--photons", but not "min" -> "max"); the first of equals.
template <typename Names>
std::optional<std::string> nearest_name(std::string_view typed, const Names& accepted) {
  std::optional<std::string> nearest;
  std::size_t best = typed.size() / 3 + 1;
  for (const auto& candidate : accepted) {
    const std::size_t distance = edit_distance(typed, candidate);
    if (distance < best) {
      best = distance;
      nearest = std::string(candidate);
    }
  }
  return nearest;
}

}  // namespace scatterlab
