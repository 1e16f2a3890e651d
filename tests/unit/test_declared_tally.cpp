// [[tally]] in a scene: read once, checked with the field named, lowered to chained tallies
// whose filters bin events themselves (transport/declared_tally.hpp, tally/scorer.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "input_error_field.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"

namespace scatterlab {
namespace {

using test_support::field_of;

std::string refused(std::string_view text) {
  return field_of([&] { parse_scene(text, "tally.toml"); });
}

constexpr std::string_view kHalfSpaceInMm =
    "[geometry]\ntype = \"half_space\"\n[medium]\nalbedo = 0.9\nsigma_t = 2\ng = 0\n"
    "length_unit = \"mm\"\n";

TEST(DeclaredTally, ReadsNameScoreAndFiltersInSpaceTimeOrder) {
  const Scene scene = parse_scene(
      std::string(kHalfSpaceInMm) +
          "[[tally]]\nname = \"R_rt\"\nscore = \"exitance\"\n"
          "filters = { t = { max = 2e-9, bins = 40 }, r = { max = 3, bins = 30 } }\n"
          "[[tally]]\nname = \"A_z\"\nscore = \"absorbed\"\nfilters = { z = { min = 0, max = 2, "
          "bins = 4 } }\n",
      "tally.toml");
  const auto& spec = std::get<HalfSpaceSpec>(scene.spec);
  ASSERT_EQ(spec.declared_tallies.size(), 2u);
  const DeclaredTally& rt = spec.declared_tallies[0];
  EXPECT_EQ(rt.name, "R_rt");
  EXPECT_EQ(rt.score, Score::exitance);
  ASSERT_NE(rt.filter(Coordinate::r), nullptr);
  EXPECT_EQ(rt.filter(Coordinate::r)->max, 3.0);
  EXPECT_FALSE(rt.filter(Coordinate::r)->min);  // 0 by default, where it is lowered
  EXPECT_EQ(rt.filter(Coordinate::t)->bins, 40);
  EXPECT_EQ(rt.filter(Coordinate::z), nullptr);

  const TransportProblem problem = transport_problem(scene.spec);
  const TallyDeclaration& d = problem.tallies.at(problem.tallies.size() - 2);
  EXPECT_TRUE(d.chained);
  EXPECT_EQ(d.score, Score::exitance);
  ASSERT_EQ(d.filters.size(), 2u);
  EXPECT_EQ(d.filters[0].dims, std::vector<std::string>{"r"});  // r before t, as written or not
  EXPECT_EQ(d.filters[1].dims, std::vector<std::string>{"t"});
  EXPECT_EQ(d.units, (Units{1, -2, 0, -1}));  // W mm^-2 per J incident, once in mm
  // The walk's r is in mfp (sigma_t = 2 / mm): 3 mm is 6 mfp. Its path is in mfp, each 0.5 mm
  // at c / 1.3 (eta).
  EXPECT_EQ(d.filters[0].binning.bin({5.9, 0.0, 0.0, 0.0, 1.0, 0}), 29);
  EXPECT_EQ(d.filters[1].binning.seconds_per_path, 0.5e-3 * 1.3 / speed_of_light);
  ASSERT_EQ(d.axes.size(), 2u);
  EXPECT_EQ(d.axes[0].units, "mm");
  EXPECT_EQ(d.axes[1].units, "s");
  EXPECT_EQ(d.axes[1].edges.back(), 2e-9);
  EXPECT_EQ(problem.tallies.back().units, (Units{1, -1}));
}

// A chained tally's filters bin an event row-major in the order listed, and the event's cell
// gets its weight; outside any filter's axis, nothing.
TEST(DeclaredTally, TheChainBinsEachEventByItsFilters) {
  TallyDeclaration d{"rt", Score::exitance, {}, {}, ""};
  d.chained = true;
  d.filters = {radius_filter(UniformAxis{0.0, 2.0, 4}),
               time_filter(UniformAxis{0.0, 1.0, 10}, 0.1)};
  const TallyBook book({d}, false);
  const Scorer scorer(TallyAxes{}, book);
  std::vector<double> buffer(book.size(), 0.0);
  SurfaceExit exit;
  exit.x = 0.3;
  exit.y = 0.4;                                         // r = 0.5: bin 1
  scorer.chained_exit(buffer.data(), exit, Vec3::UnitZ(), 3.5, 0, 0.25);  // t = 0.35: bin 3
  scorer.chained_exit(buffer.data(), exit, Vec3::UnitZ(), 10.0, 0, 1.0);  // t = 1: past the axis
  for (std::size_t i = 0; i < buffer.size(); ++i) {
    EXPECT_EQ(buffer[i], i == 1 * 10 + 3 ? 0.25 : 0.0) << i;
  }
}

// x and y bin the event's position, each by its bin's width, and a map of both is row-major, x
// first: the exit at (0.3, -0.4) falls in x bin 1 of [0, 1) and y bin 0 of [-1, 0).
TEST(DeclaredTally, PositionFiltersBinXAndY) {
  TallyDeclaration d{"map", Score::exitance, {}, {}, ""};
  d.chained = true;
  d.filters = {position_filter(Coordinate::x, UniformAxis{0.0, 1.0, 4}),
               position_filter(Coordinate::y, UniformAxis{-1.0, 1.0, 2})};
  EXPECT_EQ(d.filters[0].dims, std::vector<std::string>{"x"});
  EXPECT_EQ(d.filters[1].dims, std::vector<std::string>{"y"});
  EXPECT_EQ(d.filters[0].measures, std::vector<double>(4, 0.25));
  const TallyBook book({d}, false);
  const Scorer scorer(TallyAxes{}, book);
  std::vector<double> buffer(book.size(), 0.0);
  SurfaceExit exit;
  exit.x = 0.3;
  exit.y = -0.4;
  scorer.chained_exit(buffer.data(), exit, Vec3::UnitZ(), 0.0, 0, 0.5);
  exit.x = -0.1;  // off the x axis
  scorer.chained_exit(buffer.data(), exit, Vec3::UnitZ(), 0.0, 0, 1.0);
  for (std::size_t i = 0; i < buffer.size(); ++i) {
    EXPECT_EQ(buffer[i], i == 1 * 2 + 0 ? 0.5 : 0.0) << i;
  }
  EXPECT_THROW(position_filter(Coordinate::t, UniformAxis{0.0, 1.0, 4}), std::invalid_argument);
}

// theta_o bins the exit's angle outside, per steradian; order the scatterings, its last bin
// holding that order and more.
TEST(DeclaredTally, ExitAngleAndOrderBinTheirEvents) {
  const Filter angle = exit_solid_angle_filter(UniformAxis{0.0, pi / 2, 3});
  TallyEvent event;
  event.cos_outside = std::cos(0.4);  // bin 0 covers [0, pi/6)
  EXPECT_EQ(angle.binning.bin(event), 0);
  event.cos_outside = std::cos(1.2);
  EXPECT_EQ(angle.binning.bin(event), 2);
  EXPECT_DOUBLE_EQ(angle.measures[0], 2 * pi * (1 - std::cos(pi / 6)));
  const Filter orders = order_filter(3);
  for (const auto& [order, bin] : {std::pair{0, 0}, {1, 1}, {2, 2}, {7, 2}}) {
    event.order = order;
    EXPECT_EQ(orders.binning.bin(event), bin) << order;
  }
  EXPECT_EQ(orders.measures, (std::vector<double>{1.0, 1.0, 1.0}));
}

// theta and phi bin the direction of travel in the lab's frame; psi and azimuth an exit point on
// a sphere (psi = pi, the antipode, in the last bin); triangle a mesh's triangle.
TEST(DeclaredTally, DirectionAndSurfaceCoordinatesBinTheirEvents) {
  TallyEvent event;
  event.u_x = -std::sqrt(0.75);  // theta = 2 pi / 3; phi just past pi, below the -x axis
  event.u_y = -std::sqrt(0.75) * 1e-9;
  event.u_z = -0.5;
  const Filter theta = polar_angle_filter(UniformAxis{0.0, pi, 4}, false);
  EXPECT_EQ(theta.binning.bin(event), 2);  // [pi / 2, 3 pi / 4)
  event.u_z = -1.0;                        // straight back: pi, in the last bin
  EXPECT_EQ(theta.binning.bin(event), 3);
  EXPECT_DOUBLE_EQ(theta.measures[0], 2 * pi * (1 - std::cos(pi / 4)));
  EXPECT_DOUBLE_EQ(polar_angle_filter(UniformAxis{0.0, pi, 4}, true).measures[0],
                   1 - std::cos(pi / 4));
  const Filter phi = azimuth_angle_filter(UniformAxis{0.0, 2 * pi, 4});
  EXPECT_EQ(phi.binning.bin(event), 2);  // pi + 1e-9: [pi, 3 pi / 2)
  event.u_y = -event.u_y;
  EXPECT_EQ(phi.binning.bin(event), 1);  // pi - 1e-9: [pi / 2, pi)
  EXPECT_DOUBLE_EQ(phi.measures[0], pi / 2);
  const Filter psi = sphere_polar_filter(UniformAxis{0.0, pi, 3}, 2.0, false);
  event.cos_polar = -1.0;  // the antipode
  EXPECT_EQ(psi.binning.bin(event), 2);
  event.cos_polar = 0.9;
  EXPECT_EQ(psi.binning.bin(event), 0);
  EXPECT_DOUBLE_EQ(psi.measures[0], 2 * pi * 4.0 * (1 - std::cos(pi / 3)));
  const Filter azimuth = sphere_azimuth_filter(UniformAxis{0.0, 2 * pi, 4}, 2.0, false);
  event.x = 0.0;
  event.y = -1.0;  // azimuth 3 pi / 2: the last bin
  EXPECT_EQ(azimuth.binning.bin(event), 3);
  EXPECT_DOUBLE_EQ(azimuth.measures[0], 2 * 4.0 * pi / 2);  // the lune: 2 R^2 x width
  // Over the whole sphere the bands, and the lunes, add up to its area; psi x azimuth, made for
  // each other, to each patch's.
  double bands = 0.0, lunes = 0.0;
  for (const double m : psi.measures) bands += m;
  for (const double m : azimuth.measures) lunes += m;
  EXPECT_NEAR(bands, 4 * pi * 4.0, 1e-12);
  EXPECT_NEAR(lunes, 4 * pi * 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(
      sphere_polar_filter(UniformAxis{0.0, pi, 3}, 2.0, true).measures[1] *
          sphere_azimuth_filter(UniformAxis{0.0, 2 * pi, 4}, 2.0, true).measures[1],
      sphere_patch_filter(UniformAxis{0.0, pi, 3}, UniformAxis{0.0, 2 * pi, 4}, 2.0).measures[4]);
  const Filter triangles = triangle_filter({0.5, 0.25, 2.0});
  event.triangle = 2;
  EXPECT_EQ(triangles.binning.bin(event), 2);
}

TEST(DeclaredTally, RefusesWhatItsGeometryCannotScoreNamingTheField) {
  const std::string tally = "[[tally]]\nname = \"x\"\n";
  const std::string half(kHalfSpaceInMm);
  EXPECT_EQ(refused(half + tally + "score = \"glow\"\n"), "tally[1].score");
  EXPECT_EQ(refused(half + tally), "tally[1].score");  // missing
  EXPECT_EQ(refused(half + "[[tally]]\nscore = \"exitance\"\n"), "tally[1].name");
  EXPECT_EQ(refused(half + tally + "score = \"transmittance\"\n"), "tally[1].score");
  EXPECT_EQ(refused(half + tally +
                    "score = \"exitance\"\nfilters = { z = { min = 0, max = 1, "
                    "bins = 2 } }\n"),
            "tally[1].filters.z");
  EXPECT_EQ(
      refused(half + tally + "score = \"exitance\"\nfilters = { q = { max = 1, bins = 2 } }\n"),
      "tally[1].filters.q");
  EXPECT_EQ(refused(half + tally + "score = \"exitance\"\nfilters = { r = { max = 1 } }\n"),
            "tally[1].filters.r.bins");
  EXPECT_EQ(
      refused(half + tally + "score = \"exitance\"\nfilters = { t = { max = -1, bins = 2 } }\n"),
      "tally[1].filters.t");
  EXPECT_EQ(refused(half + tally + "score = \"absorbed\"\nfilters = { theta_o = { bins = 2 } }\n"),
            "tally[1].filters.theta_o");  // an absorption has no exit angle
  EXPECT_EQ(refused(half + tally +
                    "score = \"exitance\"\nfilters = { theta_o = { max = 1, "
                    "bins = 2 } }\n"),
            "tally[1].filters.theta_o.max");  // over [0, pi/2] always
  EXPECT_EQ(refused(half + tally + "score = \"exitance\"\nfilters = { order = {} }\n"),
            "tally[1].filters.order.bins");
  EXPECT_EQ(
      refused(half + tally + "score = \"exitance\"\nfilters = { rho = { max = 1, bins = 2 } }\n"),
      "tally[1].filters.rho");  // an exit is on the surface: r, not rho
  // x and y may be negative, so they have no default min.
  EXPECT_EQ(
      refused(half + tally + "score = \"exitance\"\nfilters = { x = { max = 1, bins = 2 } }\n"),
      "tally[1].filters.x.min");
  EXPECT_EQ(refused(half + tally +
                    "score = \"absorbed\"\nfilters = { y = { min = 1, max = -1, bins = 2 } }\n"),
            "tally[1].filters.y");
  EXPECT_EQ(refused(half + tally + "score = \"absorbed\"\nfilters = { layer = true }\n"),
            "tally[1].filters.layer");  // only a slab has layers
  EXPECT_EQ(refused(half + tally + "score = \"exitance\"\ngroup_index = 1.4\n"),
            "tally[1].group_index");
  EXPECT_EQ(refused(half + tally + "score = \"exitance\"\n" + tally + "score = \"absorbed\"\n"),
            "tally[2].name");
  // The half-space's own R(r): refused where the run is lowered, before any photon runs.
  const Scene taken =
      parse_scene(half + "[[tally]]\nname = \"reflectance\"\nscore = \"exitance\"\n", "t.toml");
  EXPECT_EQ(field_of([&] { transport_problem(taken.spec); }), "tally[1].name");
  EXPECT_EQ(refused(half + "[[tally]]\nname = \"a b\"\nscore = \"exitance\"\n"), "tally[1].name");
  // Time needs lengths in metres.
  EXPECT_EQ(refused("[geometry]\ntype = \"half_space\"\n" + tally +
                    "score = \"exitance\"\nfilters = { t = { max = 1e-9, bins = 2 } }\n"),
            "tally[1].filters.t");
  // The infinite medium has no surface and no index of its own.
  const std::string infinite = "[medium]\nsigma_a = 0.1\nsigma_s = 10\ng = 0.9\n";
  EXPECT_EQ(refused(infinite + tally + "score = \"exitance\"\n"), "tally[1].score");
  EXPECT_EQ(refused(infinite + tally +
                    "score = \"absorbed\"\nfilters = { t = { max = 1e-9, bins = 2 } }\n"),
            "tally[1].group_index");
  EXPECT_EQ(refused(infinite + tally +
                    "score = \"absorbed\"\n[tallies]\nestimator = "
                    "\"track_length\"\n"),
            "tallies.estimator");
  // The direction's theta is of events in the volume; an exit has theta_o. phi bins exits
  // through a plane only, psi and azimuth a sphere's, triangle a mesh's.
  EXPECT_EQ(refused(half + tally + "score = \"exitance\"\nfilters = { theta = { bins = 2 } }\n"),
            "tally[1].filters.theta");
  EXPECT_EQ(refused(half + tally + "score = \"exitance\"\nfilters = { psi = { bins = 2 } }\n"),
            "tally[1].filters.psi");
  const std::string sphere =
      "[geometry]\ntype = \"sphere\"\nradius = 1\neta = 1.3\n[source]\ntype = \"directional\"\n";
  EXPECT_EQ(refused(sphere + tally + "score = \"exitance\"\nfilters = { phi = { bins = 2 } }\n"),
            "tally[1].filters.phi");
  EXPECT_EQ(refused(sphere + tally + "score = \"exitance\"\nfilters = { triangle = true }\n"),
            "tally[1].filters.triangle");
  EXPECT_NO_THROW(parse_scene(sphere + tally +
                                  "score = \"exitance\"\nfilters = { psi = { bins = 2 }, "
                                  "azimuth = { bins = 3 } }\n",
                              "sphere.toml"));
  EXPECT_NO_THROW(parse_scene(sphere + tally +
                                  "score = \"absorbed\"\nfilters = { theta = { bins = 2 }, "
                                  "phi = { bins = 3 } }\n",
                              "sphere.toml"));
  // A slab's walk keeps the optical path, not the path's length; the infinite medium has no
  // surface to leave through.
  const std::string slab =
      "[geometry]\ntype = \"slab\"\n[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0\nn = 1.4\n"
      "thickness = 0.1\n";
  EXPECT_EQ(refused(slab + tally + "score = \"path_length\"\n"), "tally[1].score");
  EXPECT_EQ(refused(slab + tally + "score = \"collisions\"\n"), "tally[1].score");
  EXPECT_EQ(refused(infinite + tally + "score = \"path_length\"\n"), "tally[1].score");
  EXPECT_NO_THROW(parse_scene(half + tally + "score = \"path_length\"\n", "half.toml"));
  // A slab has no volume estimator.
  EXPECT_EQ(refused("[geometry]\ntype = \"slab\"\n[[layers]]\nmu_a = 1\nmu_s = 10\ng = 0\nn = 1.4\n"
                    "thickness = 0.1\n" +
                    tally + "score = \"fluence\"\n"),
            "tally[1].score");
  EXPECT_EQ(refused("[geometry]\ntype = \"mesh\"\n[mesh]\nshape = \"sphere\"\n" + tally +
                    "score = \"exitance\"\nfilters = { psi = { bins = 2 } }\n"),
            "tally[1].filters.psi");
  EXPECT_NO_THROW(parse_scene(infinite + tally +
                                  "score = \"absorbed\"\ngroup_index = 1.4\nfilters = { t = { "
                                  "max = 1e-9, bins = 2 }, z = { min = -1, max = 1, bins = 4 } }\n",
                              "tally.toml"));
}

// A scene without [[tally]] keeps the fingerprint it always had; one with them has its own.
TEST(DeclaredTally, OnlyADeclaredTallyChangesTheFingerprint) {
  const Scene plain = parse_scene(kHalfSpaceInMm, "a.toml");
  HalfSpaceSpec spec = std::get<HalfSpaceSpec>(plain.spec);
  const std::string before = fingerprint(plain.spec);
  spec.declared_tallies.clear();
  EXPECT_EQ(fingerprint(SceneSpec(spec)), before);
  spec.declared_tallies.push_back(
      {"R_t", Score::exitance, {{Coordinate::t, 0.0, 1e-9, 4}}, std::nullopt});
  EXPECT_NE(fingerprint(SceneSpec(spec)), before);
}

}  // namespace
}  // namespace scatterlab
