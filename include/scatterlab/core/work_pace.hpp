#pragma once
// The pace of a piece of work counted in units (batches, tiles, bins), part of which may have
// been done before this process started (a run resumed from a checkpoint): the rate and the time
// left count only the units this process did in the time it has run, so that the work resumed
// does not read as done at infinite speed.

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>

namespace scatterlab {

// Called as units of work finish (from one thread): how many are done, of how many.
using WorkProgress = std::function<void(std::uint64_t done, std::uint64_t total)>;

struct WorkPace {
  std::uint64_t done = 0;  // of `total`, including `done_before`
  std::uint64_t total = 0;
  std::uint64_t done_before = 0;  // by an earlier process
  double seconds = 0.0;           // this process has run

  // Units per second of this process; NaN before any time has passed.
  double units_per_second() const {
    if (!(seconds > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return static_cast<double>(done - done_before) / seconds;
  }

  // The units left at this process's rate; 0 when done, NaN while it has done none (no rate yet).
  double seconds_left() const {
    if (done >= total) return 0.0;
    if (done <= done_before) return std::numeric_limits<double>::quiet_NaN();
    return seconds * static_cast<double>(total - done) / static_cast<double>(done - done_before);
  }
};

// "41 s", "3 min", "2.5 h", "--" for NaN: the resolution a reader of an ETA wants.
inline std::string duration_text(double seconds) {
  if (std::isnan(seconds)) return "--";
  if (seconds < 90.0) return fmt::format("{:.0f} s", seconds);
  if (seconds < 90.0 * 60.0) return fmt::format("{:.0f} min", seconds / 60.0);
  return fmt::format("{:.1f} h", seconds / 3600.0);
}

}  // namespace scatterlab
