#pragma once
// Counter-based randomness: a photon's stream is a pure function of (seed, photon index), so a
// result does not depend on how photons are spread over threads or ranks (docs/architecture.md,
// "Randomness"). One Philox4x32-10 call (Salmon et al. 2011) gives four 32-bit words.

#include <Random123/philox.h>

#include <array>
#include <cstdint>

namespace scatterlab {

class PhotonRandom {
 public:
  // `calls`: where the stream starts, for a walk that continues it after that many calls.
  PhotonRandom(std::uint64_t seed, std::uint64_t photon_index, std::uint32_t calls = 0)
      : key_{{low(seed), high(seed)}},
        counter_{{low(photon_index), high(photon_index), calls, 0}} {}

  // Four independent uniforms in the open interval (0, 1): never 0, so -log(u) is finite, and
  // never 1, so a sampled cosine stays inside [-1, 1].
  std::array<double, 4> next4() {
    const auto words = philox_(counter_, key_);
    ++counter_[2];
    return {open_unit(words[0]), open_unit(words[1]), open_unit(words[2]), open_unit(words[3])};
  }

  // One uniform in (0, 1); spends a whole Philox call, so prefer next4() in hot loops.
  double next() { return next4()[0]; }

  // The Philox calls made so far: the counter's third word, where the next call starts (the lane
  // walk, transport/lane_walk.hpp, carries it between the calls it makes for all lanes at once).
  std::uint32_t calls() const { return counter_[2]; }

 private:
  static std::uint32_t low(std::uint64_t v) { return static_cast<std::uint32_t>(v); }
  static std::uint32_t high(std::uint64_t v) { return static_cast<std::uint32_t>(v >> 32); }
  // (k + 1/2) / 2^32: the midpoints of 2^32 equal cells of (0, 1).
  static double open_unit(std::uint32_t k) { return (static_cast<double>(k) + 0.5) * 0x1p-32; }

  r123::Philox4x32 philox_;
  r123::Philox4x32::key_type key_;
  r123::Philox4x32::ctr_type counter_;
};

}  // namespace scatterlab
