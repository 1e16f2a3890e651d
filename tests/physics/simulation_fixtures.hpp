#pragma once
// Small helpers shared by the statistical tests: run a spec, find a tally by name.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scatterlab/transport/simulate.hpp"

namespace scatterlab::testing {

inline const TallyResult& find_tally(const TransportOutput& output, const std::string& name) {
  for (const TallyResult& t : output.tallies) {
    if (t.name == name) return t;
  }
  ADD_FAILURE() << "no tally named " << name;
  static const TallyResult none{};
  return none;
}

inline double scalar(const TransportOutput& output, const std::string& name) {
  return find_tally(output, name).mean.at(0);
}

inline double scalar_error(const TransportOutput& output, const std::string& name) {
  return find_tally(output, name).stderr_of_mean.at(0);
}

// A lit object's totals (the sphere's or a mesh's): reflected at entry, exited and absorbed sum
// to 1 photon by photon, and the orders of exited and absorbed to their totals.
inline void expect_lit_object_balance(const TransportOutput& out, const std::string& label) {
  EXPECT_NEAR(scalar(out, "reflected_at_entry") + scalar(out, "exited") + scalar(out, "absorbed"),
              1.0, 1e-12)
      << label;
  for (const std::string total : {"exited", "absorbed"}) {
    EXPECT_NEAR(scalar(out, total + "_unscattered") + scalar(out, total + "_single") +
                    scalar(out, total + "_multiple"),
                scalar(out, total), 1e-12)
        << label << " " << total;
  }
}

// A small beam scene on the paper's grid, coarse in angle so tests run fast.
inline InfiniteMediumSpec small_beam(double albedo, double g, std::uint64_t photons) {
  InfiniteMediumSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.run.photons = photons;
  spec.run.batches = 32;
  spec.run.threads = 2;
  spec.grid.theta.bins = 6;
  spec.grid.phi.bins = 8;
  return spec;
}

inline void expect_all_finite(const TransportOutput& output) {
  for (const TallyResult& t : output.tallies) {
    for (std::size_t i = 0; i < t.size(); ++i) {
      ASSERT_TRUE(std::isfinite(t.mean[i]) && std::isfinite(t.stderr_of_mean[i]))
          << t.name << "[" << i << "]";
    }
  }
}

}  // namespace scatterlab::testing
