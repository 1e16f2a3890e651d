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
#include "scatterlab/tally/units.hpp"

namespace scatterlab {

struct TallyDeclaration {
  std::string name;  // e.g. "fluence"; per-order siblings append _unscattered etc.
  Score score;
  std::vector<Filter> filters;  // none: a scalar
  Units units;                  // of the finished tally, e.g. {1, -2}: W mfp^-2 per W incident
  std::string description;      // one line; the per-order siblings say which light they hold
  bool by_order = false;        // has per-order siblings when the run splits by scattering order
  double exact_value = 0.0;     // Score::exact only
  // Its filters bin its events themselves (Filter::bin; the Scorer's chain): a tally a scene
  // declares ([[tally]]), of the score's event (exitance, transmittance, fluence at collisions
  // or absorbed) at any filters. Several may share a score and filters. Never split by order.
  // Otherwise the Scorer's fixed path for its score and its filters' coordinates scores it, and
  // the run holds one tally of that pair at most.
  bool chained = false;
  std::vector<TallyAxis> axes = {};  // a chained tally's axes, as the file gives them
};

}  // namespace scatterlab
