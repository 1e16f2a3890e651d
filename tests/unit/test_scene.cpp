// Scene files: defaults, every table, the coefficient form, and one clear error per bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/transport/simulation.hpp"
#include "scene_of.hpp"

namespace scatterlab {
namespace {

using testing::load_as;
using testing::read_as;
using testing::SceneOf;

const std::filesystem::path scenes_dir =
    std::filesystem::path(SCATTERLAB_SOURCE_DIR) / "data" / "scenes";

void expect_same_spec(const InfiniteMediumSpec& a, const InfiniteMediumSpec& b) {
  EXPECT_EQ(a.medium.albedo, b.medium.albedo);
  EXPECT_EQ(a.medium.sigma_t, b.medium.sigma_t);
  EXPECT_EQ(a.medium.g, b.medium.g);
  EXPECT_EQ(a.medium.length_unit, b.medium.length_unit);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.grid.r, b.grid.r);
  EXPECT_EQ(a.grid.z, b.grid.z);
  EXPECT_EQ(a.grid.theta, b.grid.theta);
  EXPECT_EQ(a.grid.phi, b.grid.phi);
  EXPECT_EQ(a.grid.fold_phi, b.grid.fold_phi);
  EXPECT_EQ(a.grid.rho, b.grid.rho);
  EXPECT_EQ(a.tallies.radiance, b.tallies.radiance);
  EXPECT_EQ(a.tallies.fluence, b.tallies.fluence);
  EXPECT_EQ(a.tallies.flux, b.tallies.flux);
  EXPECT_EQ(a.tallies.fluence_spherical, b.tallies.fluence_spherical);
  EXPECT_EQ(a.tallies.split_by_order, b.tallies.split_by_order);
  EXPECT_EQ(a.tallies.estimator, b.tallies.estimator);
  EXPECT_EQ(a.run.photons, b.run.photons);
  EXPECT_EQ(a.run.batches, b.run.batches);
  EXPECT_EQ(a.run.seed, b.run.seed);
  EXPECT_EQ(a.run.threads, b.run.threads);
  EXPECT_EQ(a.run.escape_radius, b.run.escape_radius);
}

SceneOf<InfiniteMediumSpec> parse(std::string_view text) {
  return read_as<InfiniteMediumSpec>(text, "test.toml");
}

// The error parsing `text` raises; fails the test when there is none.
InputError error_of(std::string_view text) {
  try {
    parse(text);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError("<none>", "", "");
}

std::string field_of(std::string_view text) {
  return error_of(text).field();
}

std::string message_of(std::string_view text) {
  return error_of(text).what();
}

TEST(InfiniteMediumSpec, DefaultsAreThePapersCase) {
  const InfiniteMediumSpec spec;
  EXPECT_EQ(spec.medium.albedo, 0.5);
  EXPECT_EQ(spec.medium.g, 0.9);
  EXPECT_EQ(spec.medium.sigma_t, 1.0);
  EXPECT_EQ(spec.source, SourceKind::pencil_beam);
  EXPECT_EQ(spec.grid.r, (UniformAxis{0.0, 1.5, 15}));
  EXPECT_EQ(spec.grid.z, (UniformAxis{-1.0, 3.0, 40}));
  EXPECT_EQ(spec.grid.theta, (UniformAxis{0.0, std::numbers::pi, 18}));
  EXPECT_EQ(spec.grid.phi, (UniformAxis{0.0, 2.0 * std::numbers::pi, 36}));
  EXPECT_EQ(spec.tallies.estimator, Estimator::collision);
  EXPECT_NO_THROW(spec.validate());
}

TEST(InfiniteMediumSpec, NamesOfEnums) {
  EXPECT_EQ(to_string(SourceKind::pencil_beam), "beam");
  EXPECT_EQ(to_string(SourceKind::point), "point");
  EXPECT_EQ(to_string(Estimator::collision), "collision");
  EXPECT_EQ(to_string(Estimator::track_length), "track_length");
}

TEST(InfiniteMediumSpec, ValidateNamesTheFirstBadField) {
  const auto field_of_invalid = [](auto change) {
    InfiniteMediumSpec spec;
    change(spec);
    try {
      spec.validate();
    } catch (const InputError& error) {
      return error.field();
    }
    return std::string("<none>");
  };
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.grid.r.min = 0.5; }), "grid.r.min");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.grid.z.max = -1.0; }), "grid.z.max");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.grid.theta.max = 3.0; }),
            "grid.theta.max");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.grid.fold_phi = true; }),
            "grid.phi.max");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.grid.rho.max = 0.0; }), "grid.rho.max");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.grid.theta.bins = 100'001; }),
            "grid.theta.bins");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) {
              s.grid.r.bins = s.grid.z.bins = s.grid.theta.bins = s.grid.phi.bins = 200;
            }),
            "grid");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) {
              s.run.batches = 11;
              s.run.photons = 10;
            }),
            "run.batches");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.run.threads = -1; }), "run.threads");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.run.escape_radius = 0.0; }),
            "run.escape_radius");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.tallies.fluence_spherical = true; }),
            "tallies.fluence_spherical");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) {
              s.tallies.radiance = s.tallies.fluence = s.tallies.flux = false;
            }),
            "tallies");
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) { s.medium.length_unit = "furlong"; }),
            "medium.length_unit");
  // A huge radiance grid is fine when the radiance tally is off.
  EXPECT_EQ(field_of_invalid([](InfiniteMediumSpec& s) {
              s.grid.r.bins = s.grid.z.bins = s.grid.theta.bins = s.grid.phi.bins = 200;
              s.tallies.radiance = false;
            }),
            "<none>");
}

TEST(Scene, EmptyFileGivesTheDefaults) {
  const auto scene = parse("");
  expect_same_spec(scene.spec, InfiniteMediumSpec{});
  EXPECT_FALSE(scene.output_path.has_value());
}

TEST(Scene, EveryTableParses) {
  const auto scene = parse(R"(
    [medium]
    albedo = 0.8
    sigma_t = 2.5
    g = -0.3
    length_unit = "cm"

    [source]
    type = "point"

    [grid]
    r = { max = 2.0, bins = 20 }
    z = { min = -2, max = 4.0, bins = 30 }
    theta = { bins = 9 }
    phi = { bins = 12 }
    fold_phi = true
    rho = { max = 5.0, bins = 50 }

    [tallies]
    radiance = false
    fluence = true
    flux = false
    fluence_spherical = true
    split_by_order = true
    estimator = "track_length"

    [run]
    photons = 1e6
    batches = 10
    seed = 42
    threads = 3
    escape_radius = 100

    [output]
    path = "out/run.h5"
  )");
  const InfiniteMediumSpec& spec = scene.spec;
  EXPECT_EQ(spec.medium.albedo, 0.8);
  EXPECT_EQ(spec.medium.sigma_t, 2.5);
  EXPECT_EQ(spec.medium.g, -0.3);
  EXPECT_EQ(spec.medium.length_unit, "cm");
  EXPECT_EQ(spec.source, SourceKind::point);
  EXPECT_EQ(spec.grid.r, (UniformAxis{0.0, 2.0, 20}));
  EXPECT_EQ(spec.grid.z, (UniformAxis{-2.0, 4.0, 30}));
  EXPECT_EQ(spec.grid.theta, (UniformAxis{0.0, std::numbers::pi, 9}));
  EXPECT_EQ(spec.grid.phi, (UniformAxis{0.0, std::numbers::pi, 12}));
  EXPECT_TRUE(spec.grid.fold_phi);
  EXPECT_EQ(spec.grid.rho, (UniformAxis{0.0, 5.0, 50}));
  EXPECT_FALSE(spec.tallies.radiance);
  EXPECT_TRUE(spec.tallies.fluence);
  EXPECT_FALSE(spec.tallies.flux);
  EXPECT_TRUE(spec.tallies.fluence_spherical);
  EXPECT_TRUE(spec.tallies.split_by_order);
  EXPECT_EQ(spec.tallies.estimator, Estimator::track_length);
  EXPECT_EQ(spec.run.photons, 1'000'000u);
  EXPECT_EQ(spec.run.batches, 10u);
  EXPECT_EQ(spec.run.seed, 42u);
  EXPECT_EQ(spec.run.threads, 3);
  EXPECT_EQ(spec.run.escape_radius, 100.0);
  ASSERT_TRUE(scene.output_path.has_value());
  EXPECT_EQ(*scene.output_path, "out/run.h5");
}

TEST(Scene, DottedKeysAndSubTablesAreTheSameAsInlineTables) {
  const auto scene = parse("[grid.r]\nmax = 3.0\nbins = 30\n[grid]\nz.bins = 8\n");
  EXPECT_EQ(scene.spec.grid.r, (UniformAxis{0.0, 3.0, 30}));
  EXPECT_EQ(scene.spec.grid.z.bins, 8);
}

TEST(Scene, CoefficientFormConverts) {
  const Medium medium = parse("[medium]\nsigma_a = 0.1\nsigma_s = 0.9\ng = 0.5\n").spec.medium;
  EXPECT_NEAR(medium.albedo, 0.9, 1e-15);
  EXPECT_NEAR(medium.sigma_t, 1.0, 1e-15);
  EXPECT_EQ(medium.g, 0.5);
  EXPECT_EQ(medium.length_unit, "mm");
}

TEST(Scene, PointSourceTalliesSphericalFluenceUnlessTold) {
  EXPECT_TRUE(parse("[source]\ntype = \"point\"\n").spec.tallies.fluence_spherical);
  EXPECT_FALSE(parse("[source]\ntype = \"point\"\n[tallies]\nfluence_spherical = false\n")
                   .spec.tallies.fluence_spherical);
  EXPECT_FALSE(parse("[source]\ntype = \"beam\"\n").spec.tallies.fluence_spherical);
}

TEST(Scene, FoldPhiFalseKeepsTheFullCircle) {
  EXPECT_EQ(parse("[grid]\nfold_phi = false\n").spec.grid.phi.max, 2.0 * std::numbers::pi);
}

TEST(Scene, OutOfRangeValuesNameTheField) {
  EXPECT_EQ(field_of("[medium]\nalbedo = 1.5\n"), "medium.albedo");
  EXPECT_EQ(field_of("[medium]\ng = 1.0\n"), "medium.g");
  EXPECT_EQ(field_of("[medium]\ng = -1\n"), "medium.g");
  EXPECT_EQ(field_of("[medium]\nsigma_t = 0\nlength_unit = \"mm\"\n"), "medium.sigma_t");
  EXPECT_EQ(field_of("[medium]\nsigma_a = -0.1\nsigma_s = 0.9\n"), "medium.sigma_a");
  EXPECT_EQ(field_of("[run]\nphotons = 0\n"), "run.photons");
  EXPECT_EQ(field_of("[run]\nbatches = 1\n"), "run.batches");
  EXPECT_EQ(field_of("[run]\nphotons = 10\nbatches = 64\n"), "run.batches");
  EXPECT_EQ(field_of("[grid]\nr = { max = 0 }\n"), "grid.r.max");
  EXPECT_EQ(field_of("[grid]\nr = { max = -1.5 }\n"), "grid.r.max");
  EXPECT_EQ(field_of("[grid]\nz = { min = 3.0, max = 3.0 }\n"), "grid.z.max");
  EXPECT_EQ(field_of("[grid]\ntheta = { bins = 0 }\n"), "grid.theta.bins");
  EXPECT_EQ(field_of("[grid]\nphi = { bins = 100001 }\n"), "grid.phi.bins");
  EXPECT_EQ(field_of("[run]\nescape_radius = -1.0\n"), "run.escape_radius");
  EXPECT_EQ(field_of("[run]\nescape_radius = nan\n"), "run.escape_radius");
  EXPECT_EQ(field_of("[tallies]\nfluence_spherical = true\n"), "tallies.fluence_spherical");
  EXPECT_EQ(field_of("[tallies]\nradiance = false\nfluence = false\nflux = false\n"), "tallies");
}

TEST(Scene, MessagesSayWhatIsAccepted) {
  const std::string message = message_of("[medium]\nalbedo = 1.5\n");
  EXPECT_NE(message.find("1.5"), std::string::npos) << message;
  EXPECT_NE(message.find("[0, 1]"), std::string::npos) << message;
}

TEST(Scene, AlbedoOneNeedsAnEscapeRadius) {
  const InputError error = error_of("[medium]\nalbedo = 1\n");
  EXPECT_EQ(error.field(), "run.escape_radius");
  EXPECT_NE(std::string(error.what()).find("never absorbs"), std::string::npos) << error.what();
  EXPECT_EQ(field_of("[medium]\nalbedo = 1.0\n[run]\nescape_radius = inf\n"), "run.escape_radius");

  const auto scene = parse("[medium]\nalbedo = 1\n[run]\nescape_radius = 50.0\n");
  EXPECT_EQ(scene.spec.medium.albedo, 1.0);
  EXPECT_EQ(scene.spec.run.escape_radius, 50.0);
}

TEST(Scene, UnknownKeysAndTablesAreNamedWithTheirPath) {
  const InputError key = error_of("[medium]\nalbdo = 0.5\n");
  EXPECT_EQ(key.field(), "medium.albdo");
  const std::string key_message = key.what();
  EXPECT_NE(key_message.find("did you mean \"albedo\""), std::string::npos) << key_message;
  EXPECT_NE(key_message.find("sigma_s"), std::string::npos) << key_message;  // lists accepted
  EXPECT_NE(key_message.find("test.toml:2:1"), std::string::npos) << key_message;

  EXPECT_EQ(field_of("[meduim]\nalbedo = 0.5\n"), "meduim");
  EXPECT_NE(message_of("[meduim]\nalbedo = 0.5\n").find("unknown table"), std::string::npos);
  EXPECT_EQ(field_of("albedo = 0.5\n"), "albedo");
  EXPECT_EQ(field_of("[grid]\nr = { max = 1.0, min = 0.0 }\n"), "grid.r.min");
  EXPECT_EQ(field_of("[grid.theta]\nmax = 3.0\n"), "grid.theta.max");
  EXPECT_EQ(field_of("[grid.psi]\nbins = 3\n"), "grid.psi");
  EXPECT_EQ(field_of("[run]\nphotons = 100\nbatches = 10\nseeds = 4\n"), "run.seeds");
  EXPECT_EQ(field_of("[output]\nfile = \"a.h5\"\n"), "output.file");
}

TEST(Scene, WrongTypesNameTheKey) {
  EXPECT_EQ(field_of("[medium]\nalbedo = \"half\"\n"), "medium.albedo");
  EXPECT_NE(message_of("[medium]\nalbedo = \"half\"\n").find("a string (\"half\")"),
            std::string::npos);
  EXPECT_EQ(field_of("[medium]\ng = true\n"), "medium.g");
  EXPECT_EQ(field_of("[run]\nphotons = -5\n"), "run.photons");
  EXPECT_EQ(field_of("[run]\nphotons = 1.5e6\nbatches = 2.5\n"), "run.batches");
  EXPECT_EQ(field_of("[run]\nphotons = \"many\"\n"), "run.photons");
  EXPECT_EQ(field_of("[run]\nseed = -1\n"), "run.seed");
  EXPECT_EQ(field_of("[run]\nbatches = 5000000000\n"), "run.batches");
  EXPECT_EQ(field_of("[run]\nthreads = -2\n"), "run.threads");
  EXPECT_EQ(field_of("[tallies]\nradiance = 1\n"), "tallies.radiance");
  EXPECT_EQ(field_of("[tallies]\nestimator = \"path\"\n"), "tallies.estimator");
  EXPECT_EQ(field_of("[source]\ntype = \"laser\"\n"), "source.type");
  EXPECT_EQ(field_of("[source]\ntype = 1\n"), "source.type");
  EXPECT_EQ(field_of("medium = 3\n"), "medium");
  EXPECT_EQ(field_of("[[run]]\nphotons = 3\n"), "run");
  EXPECT_EQ(field_of("[grid]\nr = 1.5\n"), "grid.r");
  EXPECT_EQ(field_of("[grid]\nr = { bins = 2.5 }\n"), "grid.r.bins");
  EXPECT_EQ(field_of("[output]\npath = 3\n"), "output.path");
  EXPECT_EQ(field_of("[output]\npath = \"\"\n"), "output.path");
}

TEST(Scene, WholeNumberFloatsAreCounts) {
  EXPECT_EQ(parse("[run]\nphotons = 1e7\n").spec.run.photons, 10'000'000u);
  EXPECT_EQ(parse("[run]\nphotons = 2.5e3\nbatches = 5.0\n").spec.run.batches, 5u);
}

TEST(Scene, MediumFormsDoNotMix) {
  EXPECT_EQ(field_of("[medium]\nalbedo = 0.9\nsigma_a = 0.1\nsigma_s = 0.9\n"), "medium.albedo");
  EXPECT_EQ(field_of("[medium]\nsigma_t = 2\nsigma_a = 0.1\nsigma_s = 0.9\n"), "medium.sigma_t");
  EXPECT_EQ(field_of("[medium]\nsigma_a = 0.1\n"), "medium.sigma_s");
  EXPECT_EQ(field_of("[medium]\nsigma_s = 0.1\n"), "medium.sigma_a");
  EXPECT_EQ(field_of("[medium]\nsigma_a = 0\nsigma_s = 0\n"), "medium.sigma_s");
}

TEST(Scene, LengthUnits) {
  // In mean free paths sigma_t is 1 by definition; other values need a physical unit.
  EXPECT_EQ(field_of("[medium]\nsigma_t = 2.0\n"), "medium.length_unit");
  EXPECT_EQ(field_of("[medium]\nsigma_a = 1\nsigma_s = 1\nlength_unit = \"mfp\"\n"),
            "medium.length_unit");
  EXPECT_EQ(field_of("[medium]\nlength_unit = \"inch\"\nsigma_t = 2\n"), "medium.length_unit");
  EXPECT_EQ(
      parse("[medium]\nsigma_a = 0.5\nsigma_s = 0.5\nlength_unit = \"mfp\"\n").spec.medium.albedo,
      0.5);
  EXPECT_EQ(parse("[medium]\nsigma_t = 2.0\nlength_unit = \"mm\"\n").spec.medium.sigma_t, 2.0);
}

TEST(Scene, SyntaxErrorGivesTheLine) {
  const InputError error = error_of("[medium]\nalbedo = 0.5\ng = = 0.9\n");
  EXPECT_EQ(error.field(), "scene");
  const std::string message = error.what();
  EXPECT_NE(message.find("test.toml:3:"), std::string::npos) << message;
  EXPECT_NE(message.find("a valid TOML file"), std::string::npos) << message;

  EXPECT_EQ(field_of("[medium]\nalbedo = 0.5\nalbedo = 0.6\n"), "scene");  // duplicate key
}

TEST(Scene, ShippedScenesParse) {
  const auto paper = load_as<InfiniteMediumSpec>(scenes_dir / "paper-beam.toml");
  expect_same_spec(paper.spec, InfiniteMediumSpec{});
  EXPECT_EQ(paper.output_path, "paper-beam.h5");

  const auto point = load_as<InfiniteMediumSpec>(scenes_dir / "point-source.toml");
  EXPECT_EQ(point.spec.source, SourceKind::point);
  EXPECT_EQ(point.spec.medium.g, 0.0);
  EXPECT_EQ(point.spec.medium.albedo, 0.9);
  EXPECT_TRUE(point.spec.tallies.fluence_spherical);
  EXPECT_FALSE(point.spec.tallies.radiance);
}

TEST(Scene, UnreadableFileIsASceneError) {
  const std::filesystem::path missing = scenes_dir / "no-such-scene.toml";
  try {
    load_scene(missing);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "scene");
    EXPECT_NE(std::string(error.what()).find("no-such-scene.toml"), std::string::npos);
  }
  try {
    load_scene(scenes_dir);
    ADD_FAILURE() << "no error for a directory";
  } catch (const InputError& error) {
    EXPECT_EQ(error.field(), "scene");
  }
}

TEST(Scene, SyntaxErrorInAFileNamesTheFile) {
  const auto path = std::filesystem::temp_directory_path() / "scatterlab-test-bad-scene.toml";
  std::ofstream(path) << "[run]\nphotons = \n";
  try {
    load_scene(path);
    ADD_FAILURE() << "no error for a bad file";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(path.string() + ":2:"), std::string::npos)
        << error.what();
  }
  std::filesystem::remove(path);
}

// ---------------------------------------------------------------------------------------------
// The searchlight's scene.

std::string searchlight_field_of(std::string_view text) {
  try {
    read_as<HalfSpaceSpec>(text, "half.toml");
  } catch (const InputError& error) {
    return error.field();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return "<none>";
}

TEST(SearchlightScene, ShippedFileSpellsOutTheDefaults) {
  const SceneOf<HalfSpaceSpec> scene = load_as<HalfSpaceSpec>(scenes_dir / "searchlight.toml");
  const HalfSpaceSpec defaults;
  EXPECT_EQ(scene.spec.medium.albedo, defaults.medium.albedo);
  EXPECT_EQ(scene.spec.medium.g, defaults.medium.g);
  EXPECT_EQ(scene.spec.eta, defaults.eta);
  EXPECT_EQ(scene.spec.incidence_deg, defaults.incidence_deg);
  EXPECT_EQ(scene.spec.grid.r, defaults.grid.r);
  EXPECT_EQ(scene.spec.grid.z, defaults.grid.z);
  EXPECT_EQ(scene.spec.grid.theta_o, defaults.grid.theta_o);
  EXPECT_EQ(scene.spec.tallies.fluence, defaults.tallies.fluence);
  EXPECT_EQ(scene.spec.run.photons, defaults.run.photons);
  EXPECT_EQ(scene.spec.run.batches, defaults.run.batches);
  EXPECT_EQ(scene.spec.run.escape_radius, defaults.run.escape_radius);
  EXPECT_EQ(scene.output_path, "searchlight.h5");
}

TEST(SearchlightScene, ReadsEveryTable) {
  const SceneOf<HalfSpaceSpec> scene = read_as<HalfSpaceSpec>(
      "[medium]\nalbedo = 0.8\ng = -0.3\n[surface]\neta = 2.5\n[source]\nincidence_deg = 40\n"
      "[grid]\nr = { max = 4, bins = 8 }\nz = { max = 2, bins = 4 }\ntheta_o = { bins = 9 }\n"
      "[tallies]\nfluence = false\n[run]\nphotons = 1e4\nbatches = 8\n",
      "half.toml");
  EXPECT_EQ(scene.spec.medium.albedo, 0.8);
  EXPECT_EQ(scene.spec.medium.g, -0.3);
  EXPECT_EQ(scene.spec.eta, 2.5);
  EXPECT_EQ(scene.spec.incidence_deg, 40.0);
  EXPECT_EQ(scene.spec.grid.r, (UniformAxis{0.0, 4.0, 8}));
  EXPECT_EQ(scene.spec.grid.z, (UniformAxis{0.0, 2.0, 4}));
  EXPECT_EQ(scene.spec.grid.theta_o.bins, 9);
  EXPECT_FALSE(scene.spec.tallies.fluence);
  EXPECT_EQ(scene.spec.run.photons, 10000u);
}

TEST(SearchlightScene, BadInputNamesTheField) {
  EXPECT_EQ(searchlight_field_of("[surface]\neta = 0\n"), "surface.eta");
  EXPECT_EQ(searchlight_field_of("[surface]\nindex = 1.3\n"), "surface.index");
  EXPECT_EQ(searchlight_field_of("[source]\nincidence_deg = 95\n"), "source.incidence_deg");
  EXPECT_EQ(searchlight_field_of("[source]\ntype = \"point\"\n"), "source.type");
  EXPECT_EQ(searchlight_field_of("[grid]\nz = { min = -1 }\n"), "grid.z.min");
  EXPECT_EQ(searchlight_field_of("[grid]\nphi = { bins = 4 }\n"), "grid.phi");
  EXPECT_EQ(searchlight_field_of("[medium]\nalbedo = 1\n"), "run.escape_radius");
  EXPECT_EQ(searchlight_field_of("[medium]\nalbedo = \"high\"\n"), "medium.albedo");
}

// [medium] material: a measured medium (io/material_presets.hpp), in its table's unit.
TEST(Scene, MaterialSetsTheMediumInItsUnit) {
  const auto scene = parse("[medium]\nmaterial = \"marble\"\nchannel = \"blue\"\n");
  EXPECT_EQ(scene.spec.medium.length_unit, "mm");
  EXPECT_NEAR(scene.spec.medium.sigma_a(), 0.0071, 1e-12);
  EXPECT_NEAR(scene.spec.medium.sigma_s(), 3.00, 1e-12);
  EXPECT_EQ(scene.spec.medium.g, 0.0);
  ASSERT_TRUE(scene.material.has_value());
  EXPECT_EQ(scene.material->name, "marble");
  ASSERT_TRUE(scene.spec.material.has_value());
  EXPECT_EQ(scene.spec.material->library, "jensen2001");
  // g and length_unit apply to the material; channels sweep like any other key.
  const auto cm = parse(
      "[medium]\nmaterial = \"espresso\"\nchannel = \"red\"\ng = 0.5\nlength_unit = \"cm\"\n");
  EXPECT_EQ(cm.spec.medium.length_unit, "cm");
  EXPECT_EQ(cm.spec.medium.g, 0.5);
  EXPECT_NEAR(cm.spec.medium.sigma_s(), 2.707, 1e-12);
  const auto sweep = parse_sweep(
      "[medium]\nmaterial = \"apple\"\nchannel = [\"red\", \"green\", \"blue\"]\n", "t");
  ASSERT_EQ(sweep.size(), 3u);
  EXPECT_EQ(sweep[2].label, "channel=blue");
  EXPECT_NEAR(std::get<InfiniteMediumSpec>(sweep[2].scene.spec).medium.sigma_a(), 0.046, 1e-12);
}

TEST(Scene, MaterialBadInputNamesTheField) {
  EXPECT_EQ(field_of("[medium]\nmaterial = \"marbel\"\nchannel = \"red\"\n"), "medium.material");
  EXPECT_EQ(field_of("[medium]\nmaterial = \"marble\"\n"), "medium.channel");
  EXPECT_EQ(field_of("[medium]\nchannel = \"red\"\n"), "medium.channel");
  EXPECT_EQ(field_of("[medium]\nmaterial = \"marble\"\nchannel = \"red\"\nalbedo = 0.5\n"),
            "medium.albedo");
  EXPECT_EQ(field_of("[medium]\nmaterial = \"marble\"\nchannel = \"red\"\nsigma_s = 1\n"),
            "medium.sigma_s");
  EXPECT_EQ(field_of("[medium]\nmaterial = \"marble\"\nchannel = \"red\"\nlength_unit = \"mfp\"\n"),
            "medium.length_unit");
  EXPECT_EQ(field_of("[medium]\nmaterial = 3\n"), "medium.material");
}

// The searchlight takes the material's eta unless the scene gives one.
TEST(SearchlightScene, MaterialBringsItsEtaAndUnit) {
  const SceneOf<HalfSpaceSpec> milk = read_as<HalfSpaceSpec>(
      "[medium]\nmaterial = \"regular_milk\"\nchannel = \"red\"\n[grid]\nr = { max = 20 }\n", "t");
  EXPECT_DOUBLE_EQ(milk.spec.eta, 1.33);
  EXPECT_FALSE(milk.eta_given);
  EXPECT_EQ(milk.spec.medium.length_unit, "mm");
  EXPECT_DOUBLE_EQ(milk.spec.medium.g, 0.75);
  EXPECT_EQ(milk.spec.grid.r.max, 20.0);
  const SceneOf<HalfSpaceSpec> matched = read_as<HalfSpaceSpec>(
      "[medium]\nmaterial = \"apple\"\nchannel = \"red\"\n[geometry]\neta = 1.0\n", "t");
  EXPECT_DOUBLE_EQ(matched.spec.eta, 1.0);
  EXPECT_TRUE(matched.eta_given);
  EXPECT_EQ(searchlight_field_of("[medium]\nsigma_a = 0.01\nsigma_s = 1\nlength_unit = \"mfp\"\n"),
            "medium.length_unit");
}

// geometry.type chooses the geometry once; a file that names none has the caller's default.
TEST(GeometryTable, ChoosesTheGeometryOnce) {
  const auto spec_of = [](std::string_view text, std::string_view default_geometry) {
    return parse_scene(text, "test.toml", Validation::on_read, default_geometry).spec;
  };
  EXPECT_TRUE(std::holds_alternative<InfiniteMediumSpec>(spec_of("", "infinite")));
  EXPECT_TRUE(std::holds_alternative<HalfSpaceSpec>(spec_of("", "half_space")));
  EXPECT_TRUE(std::holds_alternative<InfiniteMediumSpec>(
      spec_of("[geometry]\ntype = \"infinite\"\n", "half_space")));
  EXPECT_TRUE(std::holds_alternative<HalfSpaceSpec>(
      spec_of("[geometry]\ntype = \"half_space\"\n", "infinite")));
  EXPECT_TRUE(std::holds_alternative<LitObjectSpec>(
      spec_of("[geometry]\ntype = \"sphere\"\n", "half_space")));
  EXPECT_EQ(field_of("[geometry]\ntype = \"cube\"\n"), "geometry.type");
  EXPECT_EQ(field_of("[geometry]\neta = 1.3\n"), "geometry.eta");  // no surface to have an index

  const SceneOf<HalfSpaceSpec> half =
      read_as<HalfSpaceSpec>("[geometry]\ntype = \"half_space\"\neta = 1.45\n", "half.toml");
  EXPECT_EQ(half.spec.eta, 1.45);
  EXPECT_EQ(searchlight_field_of("[geometry]\neta = 0\n"), "geometry.eta");
  EXPECT_EQ(searchlight_field_of("[geometry]\neta = 1.3\n[surface]\neta = 1.4\n"), "surface.eta");
}

TEST(SceneValidation, ByTheCallerLeavesAPartialSpecToBeFilledIn) {
  // Albedo 1 needs an escape radius, which code reading a partial scene may set after reading
  // (the command line reads with on_read: its scene files must be valid on their own).
  EXPECT_EQ(field_of("[medium]\nalbedo = 1\n"), "run.escape_radius");
  auto scene =
      read_as<InfiniteMediumSpec>("[medium]\nalbedo = 1\n", "scene.toml", Validation::by_caller);
  EXPECT_THROW(scene.spec.validate(), InputError);
  scene.spec.run.escape_radius = 5.0;
  EXPECT_NO_THROW(scene.spec.validate());

  SceneOf<HalfSpaceSpec> half =
      read_as<HalfSpaceSpec>("[medium]\nalbedo = 1\n", "half.toml", Validation::by_caller);
  half.spec.run.escape_radius = 5.0;
  EXPECT_NO_THROW(half.spec.validate());
  // Reading errors are not validation: they stop the read either way.
  EXPECT_THROW(parse_scene("[medium]\nalbdo = 1\n", "scene.toml", Validation::by_caller),
               InputError);
}

}  // namespace
}  // namespace scatterlab
