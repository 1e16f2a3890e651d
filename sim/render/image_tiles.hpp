#pragma once
// An image's pixels in tiles of 8 x 8, dealt to threads one at a time as they come free (OpenMP's
// dynamic schedule), so that a costly part of the image does not leave other threads idle. Each
// thread keeps its own State (counters), returned for the caller to fold; progress(tiles done,
// tiles) is called from one thread as tiles finish.

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include "scatterlab/core/work_pace.hpp"

namespace scatterlab {

// tile(x0, x1, y0, y1, state) renders the pixels i in [x0, x1), j in [y0, y1). `threads`: 0 for
// all.
template <class State, class Tile>
std::vector<State> render_tiles(int width, int height, int threads, const WorkProgress& progress,
                                Tile&& tile) {
  constexpr int side = 8;
  const int tiles_x = (width + side - 1) / side;
  const int tiles = tiles_x * ((height + side - 1) / side);
  const int team = threads > 0 ? threads : omp_get_max_threads();
  std::vector<State> states(static_cast<std::size_t>(std::max(team, omp_get_max_threads())));
  std::atomic<int> done{0};
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
  for (int t = 0; t < tiles; ++t) {
    const int x0 = (t % tiles_x) * side, y0 = (t / tiles_x) * side;
    tile(x0, std::min(x0 + side, width), y0, std::min(y0 + side, height),
         states[static_cast<std::size_t>(omp_get_thread_num())]);
    const int finished = ++done;
    if (progress && omp_get_thread_num() == 0) {
      progress(static_cast<std::uint64_t>(finished), static_cast<std::uint64_t>(tiles));
    }
  }
  return states;
}

}  // namespace scatterlab
