#include "prepare_outputs.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace scatterlab::cli {

void prepare_outputs(const OutputPlan& plan, bool root) {
  plan.check();
  if (!root) return;
  for (const auto& stale : plan.remove_stale_temporaries()) {
    fmt::print(stderr, "scatterlab: removed {}, left by a run killed while writing it\n",
               stale.string());
  }
}

}  // namespace scatterlab::cli
