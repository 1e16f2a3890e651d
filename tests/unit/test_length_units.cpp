// Physical length units (transport/length_units.hpp): a run whose medium and grid are in mm is
// the mfp run with every length scaled by sigma_t, and its tallies are the mfp tallies converted
// exactly by their length dimension. sigma_t is a power of two here, so every scaling is exact
// and the two runs see the same photons bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/transport/length_units.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace scatterlab {
namespace {

Medium in_mm(double sigma_t) {
  return Medium{0.8, sigma_t, 0.5, "mm"};
}

// An independent reading of a units text: the text with "mfp" replaced by the medium's unit, and
// in *factor sigma_t^-k for each mfp^k in it.
std::string in_unit(const std::string& units, const Medium& medium, double* factor) {
  *factor = 1.0;
  std::istringstream words(units);
  std::string word, converted;
  while (words >> word) {
    if (word == "mfp" || word.starts_with("mfp^")) {
      *factor *= std::pow(medium.sigma_t, -(word == "mfp" ? 1 : std::stoi(word.substr(4))));
      word = medium.length_unit + word.substr(3);
    }
    converted += (converted.empty() ? "" : " ") + word;
  }
  return converted;
}

TEST(LengthUnits, UnitsAreWrittenAndConvertedFromTheirPowers) {
  EXPECT_EQ((Units{1, -2, -1}.text("mfp")), "W mfp^-2 sr^-1 per W incident");
  EXPECT_EQ((Units{1, -2, 0, -1}.text("mm")), "W mm^-2 per J incident");
  EXPECT_EQ((Units{0, 1}.text("mm")), "mm");
  EXPECT_EQ((Units{1, 0, -1}.text("cm")), "W sr^-1 per W incident");
  EXPECT_EQ(Units{}.text("cm"), "W per W incident");
  const ReportedLength mm = reported_length(in_mm(2.0));
  EXPECT_EQ(mm.unit, "mm");
  EXPECT_EQ(mm.factor(Units{1, -2, -1}), 4.0);  // per mfp^2 = sigma_t^2 per mm^2
  EXPECT_EQ(mm.factor(Units{0, 1}), 0.5);       // 1 mfp = 1 / sigma_t mm
  EXPECT_EQ(mm.factor(Units{}), 1.0);
  EXPECT_EQ(reported_length(Medium{}).factor(Units{1, -2}), 1.0);
  // The independent reading of the text agrees.
  for (const Units units : {Units{1, -2, -1}, Units{0, 1}, Units{1, -3}, Units{}}) {
    double factor = 0.0;
    EXPECT_EQ(in_unit(units.text("mfp"), in_mm(2.0), &factor), units.text("mm"));
    EXPECT_EQ(factor, mm.factor(units));
  }
}

TEST(LengthUnits, UnknownUnitOrMfpWithSigmaTIsRefused) {
  auto field_of = [](const Medium& medium) {
    try {
      check_length_unit(medium);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of(Medium{0.5, 2.0, 0.0, "mfp"}), "medium.length_unit");
  EXPECT_EQ(field_of(Medium{0.5, 2.0, 0.0, "furlong"}), "medium.length_unit");
  EXPECT_EQ(field_of(Medium{0.5, 2.0, 0.0, "cm"}), "(accepted)");
  // The searchlight, which refused sigma_t != 1 before units, names the unit too.
  HalfSpaceSpec spec;
  spec.medium = Medium{0.9, 2.0, 0.0, "mfp"};
  try {
    spec.validate();
    FAIL() << "sigma_t = 2 in mfp accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "medium.length_unit");
  }
}

void expect_scaled(const std::vector<TallyResult>& mm, const std::vector<TallyResult>& mfp,
                   double sigma_t) {
  ASSERT_EQ(mm.size(), mfp.size());
  for (std::size_t t = 0; t < mm.size(); ++t) {
    double factor = 0.0;
    const std::string units = in_unit(mfp[t].units, in_mm(sigma_t), &factor);
    EXPECT_EQ(mm[t].name, mfp[t].name);
    EXPECT_EQ(mm[t].units, units) << mm[t].name;
    EXPECT_EQ(mm[t].units.find("mfp"), std::string::npos) << mm[t].units;
    ASSERT_EQ(mm[t].mean.size(), mfp[t].mean.size());
    double total = 0.0;
    for (std::size_t i = 0; i < mm[t].mean.size(); ++i) {
      // Exact: the same photons in the same bins, times a power of two.
      EXPECT_EQ(mm[t].mean[i], mfp[t].mean[i] * factor) << mm[t].name << " cell " << i;
      EXPECT_EQ(mm[t].stderr_of_mean[i], mfp[t].stderr_of_mean[i] * factor) << mm[t].name;
      total += mfp[t].mean[i];
    }
    if (mm[t].name == "fluence" || mm[t].name == "reflectance") {
      EXPECT_GT(total, 0.0);
    }
  }
}

TEST(LengthUnits, SimulateInMillimetresIsTheMfpRunScaled) {
  InfiniteMediumSpec mfp;
  mfp.medium = Medium{0.8, 1.0, 0.5, "mfp"};
  mfp.run = RunSettings{20'000, 8, 3, 2};
  mfp.run.escape_radius = 6.0;
  mfp.tallies.radiance = false;
  InfiniteMediumSpec mm = mfp;
  const double sigma_t = 2.0;  // 1/mm: 1 mfp = 0.5 mm
  mm.medium = in_mm(sigma_t);
  mm.grid.r.max = mfp.grid.r.max / sigma_t;
  mm.grid.z.min = mfp.grid.z.min / sigma_t;
  mm.grid.z.max = mfp.grid.z.max / sigma_t;
  mm.grid.rho.max = mfp.grid.rho.max / sigma_t;
  mm.run.escape_radius = mfp.run.escape_radius / sigma_t;
  const TransportOutput a = run_infinite_medium(mm);
  const TransportOutput b = run_infinite_medium(mfp);
  expect_scaled(a.tallies, b.tallies, sigma_t);
  // The mean absorption depth is a length: mm = mfp / sigma_t.
  const TallyResult* depth = find_tally(a.tallies, "absorbed_mean_depth");
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(depth->units, "mm");
  EXPECT_EQ(depth->mean[0], find_tally(b.tallies, "absorbed_mean_depth")->mean[0] / sigma_t);
}

TEST(LengthUnits, SearchlightAcceptsSigmaTInCentimetres) {
  HalfSpaceSpec mfp;
  mfp.medium = Medium{0.9, 1.0, 0.3, "mfp"};
  mfp.run = RunSettings{20'000, 8, 5, 2};
  mfp.grid.r.bins = 20;
  mfp.grid.z.bins = 10;
  HalfSpaceSpec cm = mfp;
  const double sigma_t = 4.0;  // 1/cm
  cm.medium = Medium{0.9, sigma_t, 0.3, "cm"};
  cm.grid.r.max = mfp.grid.r.max / sigma_t;
  cm.grid.z.max = mfp.grid.z.max / sigma_t;
  ASSERT_NO_THROW(cm.validate());
  const TransportOutput a = run_half_space(cm);
  const TransportOutput b = run_half_space(mfp);
  ASSERT_EQ(a.tallies.size(), b.tallies.size());
  for (std::size_t t = 0; t < a.tallies.size(); ++t) {
    double factor = 0.0;
    const std::string units = in_unit(b.tallies[t].units, cm.medium, &factor);
    EXPECT_EQ(a.tallies[t].units, units);
    for (std::size_t i = 0; i < a.tallies[t].mean.size(); ++i) {
      EXPECT_EQ(a.tallies[t].mean[i], b.tallies[t].mean[i] * factor) << a.tallies[t].name;
    }
  }
  EXPECT_EQ(find_tally(a.tallies, "reflectance")->units, "W cm^-2 per W incident");
}

// A scene in mm reads its grid keys in mm; the material's unit is the table's.
TEST(LengthUnits, SceneGridKeysAreInTheMediumsUnit) {
  const InfiniteMediumSpec spec = std::get<InfiniteMediumSpec>(
      parse_scene("[medium]\nmaterial = \"skimmilk\"\nchannel = \"green\"\n[grid]\nr = { max = 4, "
                  "bins = 8 }\n",
                  "t")
          .spec);
  EXPECT_EQ(spec.medium.length_unit, "mm");
  EXPECT_EQ(spec.grid.r.max, 4.0);
  ASSERT_TRUE(spec.material.has_value());
  EXPECT_EQ(spec.material->name, "skimmilk");
  EXPECT_EQ(spec.material->channel, "green");
  EXPECT_NEAR(spec.medium.sigma_a(), 0.0025, 1e-12);
}

}  // namespace
}  // namespace scatterlab
