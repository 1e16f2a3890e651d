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

// Throws InputError ("run.photons", "run.batches", "run.threads", "run.escape_radius") for
// settings no kernel can run; whether an infinite escape radius is allowed is the scene's call.
void check_run_settings(const RunSettings& run);

// A run's identity for checkpoints, resumes and skipped sweep points: a 64-bit FNV-1a hash
// (Fowler, Noll, Vo) of a canonical text of everything that shapes its tallies, as 16 hex
// digits. Each spec writes its own canonical text (doubles in hexadecimal, {:a}, so it is exact).
std::string fingerprint_of(std::string_view canonical);

}  // namespace scatterlab
