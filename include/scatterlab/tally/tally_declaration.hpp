#pragma once
// A tally, declared once: its name, the score it adds up, the filters that bin it, its units and
// what it means. The buffer layout (tally_book.hpp), the scorer, the finished arrays and so the
// file, merge and info all read this declaration; adding a tally is a declaration and, for a new
// kind of quantity, its score.

#include <string>
#include <vector>

#include "scatterlab/tally/filter.hpp"
#include "scatterlab/tally/score.hpp"
#include "scatterlab/tally/tally_result.hpp"

namespace scatterlab {

struct TallyDeclaration {
  std::string name;  // e.g. "fluence"; per-order siblings append _unscattered etc.
  Score score;
  std::vector<Filter> filters;  // none: a scalar
  std::string units;            // of the finished tally, e.g. "W mfp^-2 per W incident"
  std::string description;      // one line; the per-order siblings say which light they hold
  bool by_order = false;        // has per-order siblings when the run splits by scattering order
  double exact_value = 0.0;     // Score::exact only
  // Its filters bin its events themselves (Filter::bin; the Scorer's chain): a tally a scene
  // declares ([[tally]]), of the score's event (exit, transmitted, fluence at collisions or
  // absorbed) at any filters. Several may share a score. Never split by order.
  bool chained = false;
  std::vector<TallyAxis> axes = {};  // a chained tally's axes, as the file gives them
};

}  // namespace scatterlab
