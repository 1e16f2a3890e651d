// Declared tallies binned by position, x and y and the distance rho from a point source
// (transport/declared_tally.hpp): maps of where light is absorbed and where it leaves, held
// against exact densities, the symmetry of normal incidence, the geometries' own tallies and the
// identity that summing a map over y gives the map binned by x alone. Fixed seeds; tolerances
// k sigma.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"
#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

using testing::find_tally;

DeclaredFilter filter(Coordinate coordinate, const UniformAxis& axis) {
  return {coordinate, axis.min, axis.max, axis.bins};
}

// A beam enters an index-matched half-space at theta = 60 degrees in the x-z plane and every
// photon is absorbed at its first collision (albedo 0), a path s ~ exp(-s / l) from the entry
// point: at x = s sin theta, y = 0. So the power absorbed per unit x is exp(-x / a) / a,
// a = l sin theta, and a bin [x0, x1) holds exp(-x0 / a) - exp(-x1 / a) of it; every photon is
// absorbed in the one bin of y about 0, whose density is exactly 1 / its width.
TEST(PositionFilters, ObliqueBeamIsAbsorbedExponentiallyAlongX) {
  HalfSpaceSpec spec;
  const double l = 0.5;  // mm, the mean free path
  spec.medium = Medium::from_albedo(0.0, 1.0 / l, 0.0, "mm");
  spec.eta = 1.0;
  spec.incidence_deg = 60.0;
  spec.run.photons = 100'000;
  spec.run.batches = 10;
  spec.run.seed = 17;
  const double a = l * std::sin(60.0 * std::numbers::pi / 180.0);
  const UniformAxis x{0.0, 4.0 * a, 20};
  const UniformAxis y{-0.5, 0.5, 5};  // 0 is in the middle bin
  spec.declared_tallies = {
      {"absorbed_x", Score::absorbed, {filter(Coordinate::x, x)}, std::nullopt},
      {"absorbed_y", Score::absorbed, {filter(Coordinate::y, y)}, std::nullopt}};
  const TransportOutput out = run_half_space(spec);
  const TallyResult& along_x = find_tally(out, "absorbed_x");
  ASSERT_EQ(along_x.dims, std::vector<std::string>{"x"});
  EXPECT_EQ(along_x.units, "W mm^-1 per W incident");
  for (int i = 0; i < x.bins; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double exact = (std::exp(-x.edge(i) / a) - std::exp(-x.edge(i + 1) / a)) / x.width();
    EXPECT_NEAR(along_x.mean[k], exact, 4.0 * along_x.stderr_of_mean[k]) << "bin " << i;
  }
  const TallyResult& along_y = find_tally(out, "absorbed_y");
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(along_y.mean[k], k == 2 ? 1.0 / y.width() : 0.0, 1e-12) << "bin " << k;
  }
}

// At normal incidence the exitance M(x, y) is symmetric under x -> -x and x <-> y: cells that
// the symmetry maps onto each other agree within 4 sigma of their difference. It is the
// half-space's own exitance map, which the Scorer bins by its own strides, to round-off; and
// summed over its y bins (times their width) it gives, to round-off, a tally of the same exits
// binned by x with one y bin over the same span.
TEST(PositionFilters, ExitanceMapIsSymmetricAndSumsOverY) {
  HalfSpaceSpec spec;
  spec.medium = Medium::from_albedo(0.9, 2.0, 0.5, "mm");  // lengths in mm, the walk in mfp
  spec.eta = 1.4;
  spec.run.photons = 200'000;
  spec.run.batches = 10;
  spec.run.seed = 23;
  const int n = 8;
  const UniformAxis span{-2.0, 2.0, n};
  const UniformAxis whole{-2.0, 2.0, 1};
  spec.grid.x = spec.grid.y = span;
  spec.tallies.exitance_map = true;
  spec.declared_tallies = {{"map",
                            Score::exitance,
                            {filter(Coordinate::x, span), filter(Coordinate::y, span)},
                            std::nullopt},
                           {"strip",
                            Score::exitance,
                            {filter(Coordinate::x, span), filter(Coordinate::y, whole)},
                            std::nullopt}};
  const TransportOutput out = run_half_space(spec);
  const TallyResult& map = find_tally(out, "map");
  const TallyResult& strip = find_tally(out, "strip");
  const TallyResult& own = find_tally(out, "exitance_map");
  ASSERT_EQ(own.size(), map.size());
  ASSERT_EQ(map.dims, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(map.units, "W mm^-2 per W incident");
  const auto at = [&](int i, int j) { return static_cast<std::size_t>(i * n + j); };
  const auto expect_same = [&](std::size_t a, std::size_t b) {
    const double sigma = std::hypot(map.stderr_of_mean[a], map.stderr_of_mean[b]);
    EXPECT_NEAR(map.mean[a], map.mean[b], 4.0 * sigma) << "cells " << a << " and " << b;
  };
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      expect_same(at(i, j), at(n - 1 - i, j));
      expect_same(at(i, j), at(j, i));
      EXPECT_NEAR(map.mean[at(i, j)], own.mean[at(i, j)], 1e-12 * own.mean[at(i, j)]);
      sum += map.mean[at(i, j)] * span.width();
    }
    const auto k = static_cast<std::size_t>(i);
    EXPECT_NEAR(sum, strip.mean[k] * whole.width(), 1e-12 * strip.mean[k]) << "x bin " << i;
    total += sum;
  }
  EXPECT_GT(total, 0.0);
}

// An isotropic point source in a purely absorbing infinite medium (albedo 0): every photon is
// absorbed at its first collision, at a distance rho ~ exp(-rho / l) from the source, so the
// shell [rho0, rho1) holds exp(-rho0 / l) - exp(-rho1 / l) of the power, and its density is that
// over the shell's volume 4/3 pi (rho1^3 - rho0^3).
TEST(PositionFilters, PointSourceIsAbsorbedExponentiallyInRho) {
  InfiniteMediumSpec spec;
  const double l = 0.5;  // mm
  spec.medium = Medium::from_albedo(0.0, 1.0 / l, 0.0, "mm");
  spec.set_source(SourceKind::point);
  spec.tallies.radiance = spec.tallies.fluence = spec.tallies.flux = false;
  spec.run.photons = 100'000;
  spec.run.batches = 10;
  spec.run.seed = 29;
  const UniformAxis rho{0.0, 4.0 * l, 20};
  spec.declared_tallies = {
      {"absorbed_rho", Score::absorbed, {filter(Coordinate::rho, rho)}, std::nullopt}};
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& a = find_tally(out, "absorbed_rho");
  ASSERT_EQ(a.dims, std::vector<std::string>{"rho"});
  EXPECT_EQ(a.units, "W mm^-3 per W incident");
  for (int i = 0; i < rho.bins; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double r0 = rho.edge(i), r1 = rho.edge(i + 1);
    const double volume = 4.0 / 3.0 * std::numbers::pi * (r1 * r1 * r1 - r0 * r0 * r0);
    const double exact = (std::exp(-r0 / l) - std::exp(-r1 / l)) / volume;
    EXPECT_NEAR(a.mean[k], exact, 4.0 * a.stderr_of_mean[k]) << "shell " << i;
  }
}

// In a scattering medium the declared fluence on shells about a point source is the source's
// own fluence_spherical: the same collisions in the same shells, to round-off.
TEST(PositionFilters, FluenceOnShellsIsThePointSourcesOwn) {
  InfiniteMediumSpec spec;
  spec.medium = Medium::from_albedo(0.9, 2.0, 0.5, "mm");
  spec.set_source(SourceKind::point);
  spec.tallies.radiance = spec.tallies.fluence = spec.tallies.flux = false;
  spec.grid.rho = UniformAxis{0.0, 3.0, 30};
  spec.run.photons = 20'000;
  spec.run.batches = 8;
  spec.run.seed = 31;
  spec.declared_tallies = {
      {"fluence_rho", Score::fluence, {filter(Coordinate::rho, spec.grid.rho)}, std::nullopt}};
  const TransportOutput out = run_infinite_medium(spec);
  const TallyResult& declared = find_tally(out, "fluence_rho");
  const TallyResult& own = find_tally(out, "fluence_spherical");
  ASSERT_EQ(declared.size(), own.size());
  EXPECT_EQ(declared.units, own.units);
  for (std::size_t i = 0; i < own.size(); ++i) {
    EXPECT_NEAR(declared.mean[i], own.mean[i], 1e-12 * own.mean[i]) << "shell " << i;
  }
}

}  // namespace
}  // namespace scatterlab
