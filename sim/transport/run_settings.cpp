#include "scatterlab/transport/run_settings.hpp"

#include <fmt/format.h>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

void check_run_settings(const RunSettings& run) {
  if (run.photons < 1) {
    throw InputError("run.photons", fmt::format("got {}", run.photons), "an integer >= 1");
  }
  if (run.batches < 2 || run.batches > run.photons) {
    throw InputError("run.batches",
                     fmt::format("got {} with run.photons = {}", run.batches, run.photons),
                     "an integer in [2, run.photons] (a standard error needs at least 2 batches)");
  }
  if (run.threads < 0) {
    throw InputError("run.threads", fmt::format("got {}", run.threads),
                     "an integer >= 0 (0: all hardware threads)");
  }
  if (!(run.escape_radius > 0.0)) {
    throw InputError("run.escape_radius", fmt::format("got {}", run.escape_radius),
                     "a number > 0 (mfp), or inf");
  }
}

std::string fingerprint_of(std::string_view canonical) {
  // A fingerprint, not a defence against forgery.
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const char c : canonical) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ull;
  }
  return fmt::format("{:016x}", hash);
}

}  // namespace scatterlab
