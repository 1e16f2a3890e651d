#pragma once
// How many photons to run and how: shared by every transport kernel (batch_runner.hpp).

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace scatterlab {

struct RunSettings {
  std::uint64_t photons = 100'000'000;  // smooth lobes near the source in ~15 s on 2 cores
  std::uint32_t batches = 64;   // batch statistics: standard error from batch-to-batch spread
  std::uint64_t seed = 1;
  int threads = 0;              // 0: all hardware threads
  // Photons farther than this from the origin are counted as escaped and stopped. Infinite by
  // default; required when albedo = 1, where nothing is ever absorbed.
  double escape_radius = std::numeric_limits<double>::infinity();
};

// Counts of photons and of expected events stay below 2^53, where a double still holds every
// whole number (per-batch means divide by photon counts as doubles, rates print as doubles) and
// where a run is already about three years of one thread at 10 ns per event.
inline constexpr std::uint64_t max_photons = std::uint64_t{1} << 53;
inline constexpr double max_run_events = 0x1p53;

// The mean number of events (collisions) a photon takes, from above: a walk ends by absorption
// after 1 / (1 - albedo) collisions on average, and at the latest, with albedo 1, when it passes
// the escape radius R, which a diffusing photon reaches after about R^2 collisions (R in mfp).
double expected_events_per_photon(double albedo, double escape_radius_mfp);

// Throws InputError unless photons x expected_events_per_photon is at most max_run_events:
// naming "medium.albedo, run.escape_radius" when one photon alone is over, else "run.photons".
void check_run_length(const RunSettings& run, double albedo, double escape_radius_mfp);

// Throws InputError ("run.photons", "run.batches", "run.seed", "run.threads",
// "run.escape_radius") for settings no kernel can run; whether an infinite escape radius is allowed
// is the scene's call.
void check_run_settings(const RunSettings& run);

// The most threads any command may ask for: 4 per hardware thread
// (std::thread::hardware_concurrency, taken as 1 when unknown). More only shares the same cores,
// and a count far above it (100000) exhausts the process's stacks before a photon runs.
int max_threads();

// What every command accepts for a thread count, for its help text and errors.
std::string threads_accepted();

// The one check of a thread count, from any flag or key: throws InputError naming `field` unless
// 0 <= threads <= max_threads(). 0 takes OpenMP's count (OMP_NUM_THREADS, else every hardware
// thread), which is held to the same bound, naming OMP_NUM_THREADS.
void check_threads(int threads, const std::string& field);

// Seeds are what a scene file can hold (a TOML integer): [0, 2^63 - 1], on the command line too.
inline constexpr std::uint64_t max_seed = (std::uint64_t{1} << 63) - 1;
inline constexpr std::string_view seed_accepted = "an integer in [0, 2^63 - 1]";

// The one check of a seed, from any flag or key: throws InputError naming `field` above max_seed.
// A command that runs `count` seeds from `seed` upward (validate deon, report) needs all of them
// in range, and says so.
void check_seed(std::uint64_t seed, const std::string& field, std::uint64_t count = 1);

// A run's identity for checkpoints, resumes and skipped sweep points: a 64-bit FNV-1a hash
// (Fowler, Noll, Vo) of a canonical text of everything that shapes its tallies, as 16 hex
// digits. Each spec writes its own canonical text (doubles in hexadecimal, {:a}, so it is exact).
std::string fingerprint_of(std::string_view canonical);

}  // namespace scatterlab
