#include "scatterlab/transport/run_settings.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <thread>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fnv1a.hpp"

namespace scatterlab {

void check_run_settings(const RunSettings& run) {
  if (run.photons < 1 || run.photons > max_photons) {
    throw InputError("run.photons", fmt::format("got {}", run.photons),
                     "an integer in [1, 2^53 = 9007199254740992] (counts exact as doubles)");
  }
  if (run.batches < 2 || run.batches > run.photons) {
    throw InputError("run.batches",
                     fmt::format("got {} with run.photons = {}", run.batches, run.photons),
                     "an integer in [2, run.photons] (a standard error needs at least 2 batches)");
  }
  check_seed(run.seed, "run.seed");
  check_threads(run.threads, "run.threads");
  if (!(run.escape_radius > 0.0)) {
    throw InputError("run.escape_radius", fmt::format("got {}", run.escape_radius),
                     "a number > 0 (mfp), or inf");
  }
}

double expected_events_per_photon(double albedo, double escape_radius_mfp) {
  const double absorbed_after = 1.0 / (1.0 - albedo);  // inf at albedo 1
  const double escaped_after = 1.0 + escape_radius_mfp * escape_radius_mfp;
  return std::min(absorbed_after, escaped_after);
}

void check_run_length(const RunSettings& run, double albedo, double escape_radius_mfp) {
  const double per_photon = expected_events_per_photon(albedo, escape_radius_mfp);
  const double events = static_cast<double>(run.photons) * per_photon;
  if (events <= max_run_events) return;
  const std::string accepted =
      "photons x min(1 / (1 - medium.albedo), 1 + (run.escape_radius in mfp)^2), the expected "
      "events of the run, at most 2^53 (9.0e15; years on one thread): fewer photons, a lower "
      "albedo or a smaller escape radius";
  if (per_photon > max_run_events) {
    throw InputError("medium.albedo, run.escape_radius",
                     fmt::format("a photon would take about {:.3g} events before it is absorbed "
                                 "or escapes (albedo {}, escape radius {:g} mfp)",
                                 per_photon, albedo, escape_radius_mfp),
                     accepted);
  }
  throw InputError("run.photons",
                   fmt::format("got {} photons of about {:.3g} events each (albedo {}, escape "
                               "radius {:g} mfp): {:.3g} events in all",
                               run.photons, per_photon, albedo, escape_radius_mfp, events),
                   accepted);
}

int max_threads() {
  const unsigned hardware = std::max(std::thread::hardware_concurrency(), 1u);
  return static_cast<int>(std::min(4u * hardware, 1u << 20));
}

std::string threads_accepted() {
  return fmt::format(
      "an integer in [0, {}] (0: all hardware threads; at most 4 per hardware thread)",
      max_threads());
}

void check_threads(int threads, const std::string& field) {
  if (threads < 0 || threads > max_threads()) {
    throw InputError(field, fmt::format("got {}", threads), threads_accepted());
  }
  if (threads == 0 && omp_get_max_threads() > max_threads()) {
    throw InputError("OMP_NUM_THREADS",
                     fmt::format("got {} (taken for {} 0)", omp_get_max_threads(), field),
                     fmt::format("at most {} (4 per hardware thread), or a thread count in {}",
                                 max_threads(), field));
  }
}

void check_seed(std::uint64_t seed, const std::string& field, std::uint64_t count) {
  if (count <= 1) {
    if (seed > max_seed) {
      throw InputError(field, fmt::format("got {}", seed), std::string(seed_accepted));
    }
    return;
  }
  const std::uint64_t highest = max_seed - (count - 1);
  if (seed > highest) {
    throw InputError(field, fmt::format("got {}", seed),
                     fmt::format("an integer in [0, {}]: the command runs {} seeds from it upward, "
                                 "each in [0, 2^63 - 1]",
                                 highest, count));
  }
}

std::string fingerprint_of(std::string_view canonical) {
  Fnv1a hash;
  hash.add(canonical);
  return fmt::format("{:016x}", hash.value());
}

}  // namespace scatterlab
