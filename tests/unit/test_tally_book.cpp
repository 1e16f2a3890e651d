// Tallies declared once: each filter's bin measures add up to the whole they divide (exact
// identities), and the book lays out, names and finishes every declared tally and its per-order
// siblings from the declaration alone.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/tally/tally_book.hpp"

namespace scatterlab {
namespace {

double total(const Filter& f) {
  return std::accumulate(f.measures.begin(), f.measures.end(), 0.0);
}

TEST(Filter, MeasuresAddUpToTheWhole) {
  EXPECT_NEAR(total(radius_filter({0.0, 2.0, 40})), pi * 4.0, 1e-12);
  EXPECT_NEAR(total(position_filter(Coordinate::z, {-1.0, 3.0, 40})), 4.0, 1e-12);
  EXPECT_NEAR(total(shell_filter({0.0, 3.0, 30})), 4.0 / 3.0 * pi * 27.0, 1e-10);
  // All directions: 4 pi sr, folded or not (a folded bin stands for phi and -phi).
  EXPECT_NEAR(total(direction_filter({0.0, pi, 18}, {0.0, 2.0 * pi, 36}, false)), 4.0 * pi, 1e-12);
  EXPECT_NEAR(total(direction_filter({0.0, pi, 18}, {0.0, pi, 18}, true)), 4.0 * pi, 1e-12);
  // Projected solid angle of the outgoing hemisphere: integral of cos theta dw = pi.
  EXPECT_NEAR(total(exit_angle_filter({0.0, 0.5 * pi, 18})), pi, 1e-12);
  EXPECT_EQ(total(component_filter(2)), 2.0);
}

TEST(Filter, DirectionBinsAreRowMajorInThetaThenPhi) {
  const Filter f = direction_filter({0.0, pi, 2}, {0.0, 2.0 * pi, 4}, false);
  EXPECT_EQ(f.dims, (std::vector<std::string>{"theta", "phi"}));
  EXPECT_EQ(f.shape, (std::vector<std::size_t>{2, 4}));
  ASSERT_EQ(f.bins(), 8u);
  // Each hemisphere holds 2 pi sr in four phi bins of pi / 2.
  for (const double m : f.measures) EXPECT_NEAR(m, 0.5 * pi, 1e-12);
}

// Two by-order tallies, a scalar and an exact value, split by order.
std::vector<TallyDeclaration> declarations() {
  return {{"ring", Score::exitance, {radius_filter({0.0, 2.0, 2})}, Units{1, -2}, "per ring", true},
          {"total", Score::exitance, {}, Units{}, "all of it", true},
          {"absorbed", Score::absorbed, {}, Units{}, "absorbed"},
          {"specular", Score::exact, {}, Units{}, "known", false, 0.25}};
}

TEST(TallyBook, LaysOutBlocksThenTheRest) {
  const TallyBook split(declarations(), true);
  EXPECT_EQ(split.offset(Score::exitance, {Coordinate::r}), 0u);
  EXPECT_EQ(split.offset(Score::exitance), 2u);
  EXPECT_FALSE(split.has(Score::exitance, {Coordinate::r, Coordinate::exit_angle}));
  EXPECT_EQ(split.order_block(0), 3u);
  EXPECT_EQ(split.order_block(1), 6u);
  EXPECT_EQ(split.order_block(7), 9u);  // two or more
  EXPECT_EQ(split.offset(Score::absorbed), 12u);
  EXPECT_EQ(split.size(), 13u);
  EXPECT_FALSE(split.has(Score::fluence));
  EXPECT_FALSE(split.scores_volume());

  const TallyBook whole(declarations(), false);
  EXPECT_EQ(whole.offset(Score::absorbed), 3u);
  EXPECT_EQ(whole.size(), 4u);
}

TEST(TallyBook, FinishesEachTallyFromItsDeclaration) {
  const TallyBook book(declarations(), true);
  std::vector<double> mean(book.size()), error(book.size());
  for (std::size_t i = 0; i < mean.size(); ++i) {
    mean[i] = static_cast<double>(i + 1);
    error[i] = 0.1 * static_cast<double>(i + 1);
  }
  const std::vector<TallyResult> results = book.finish(mean, error, 0.5);
  std::vector<std::string> names;
  for (const TallyResult& t : results) names.push_back(t.name);
  EXPECT_EQ(names, (std::vector<std::string>{
                       "ring", "total", "ring_unscattered", "total_unscattered", "ring_single",
                       "total_single", "ring_multiple", "total_multiple", "absorbed", "specular"}));
  // ring_single: cells 6 and 7 of the buffer, divided by the ring areas, times the power 0.5.
  const TallyResult& ring_single = results[4];
  EXPECT_EQ(ring_single.dims, (std::vector<std::string>{"r"}));
  EXPECT_DOUBLE_EQ(ring_single.mean[0], 7.0 / pi * 0.5);
  EXPECT_DOUBLE_EQ(ring_single.mean[1], 8.0 / (3.0 * pi) * 0.5);
  EXPECT_DOUBLE_EQ(ring_single.stderr_of_mean[1], 0.8 / (3.0 * pi) * 0.5);
  EXPECT_EQ(ring_single.description, "per ring (light scattered exactly once)");
  EXPECT_DOUBLE_EQ(results[8].mean[0], 13.0 * 0.5);  // absorbed, a scalar
  // The exact tally is its value, unscaled, with no standard error.
  EXPECT_EQ(results[9].mean, std::vector<double>{0.25});
  EXPECT_EQ(results[9].stderr_of_mean, std::vector<double>{0.0});
}

// Each tally is written in the reported length unit, and converted by its own length power: a
// value per mfp^k is walk_per_unit^k per unit^k.
TEST(TallyBook, ReportsInTheRunsLengthUnitByEachTallysPower) {
  const TallyBook book(declarations(), false);
  const std::vector<double> mean(book.size(), 1.0), error(book.size(), 0.5);
  const std::vector<TallyResult> mfp = book.finish(mean, error, 1.0);
  const std::vector<TallyResult> mm = book.finish(mean, error, 1.0, {"mm", 2.0});
  EXPECT_EQ(mfp[0].units, "W mfp^-2 per W incident");
  EXPECT_EQ(mm[0].units, "W mm^-2 per W incident");
  EXPECT_EQ(mm[0].mean[0], mfp[0].mean[0] * 4.0);
  EXPECT_EQ(mm[0].stderr_of_mean[1], mfp[0].stderr_of_mean[1] * 4.0);
  EXPECT_EQ(mm[1].units, "W per W incident");
  EXPECT_EQ(mm[1].mean, mfp[1].mean);
}

// A fixed path scores one tally; two of one score binned along the same coordinates would be
// scored twice over. The chain takes any number.
TEST(TallyBook, RefusesTwoTalliesOfOneFixedPath) {
  std::vector<TallyDeclaration> twice = declarations();
  twice.push_back(twice.front());
  EXPECT_THROW(TallyBook(twice, false), std::invalid_argument);
  twice.back().name = "ring_r";
  twice.back().chained = true;
  twice.back().by_order = false;
  EXPECT_NO_THROW(TallyBook(twice, false));
  // Of one score along other coordinates, both have their path.
  std::vector<TallyDeclaration> two = declarations();
  two.push_back({"ring_angle",
                 Score::exitance,
                 {radius_filter({0.0, 2.0, 2}), exit_angle_filter({0.0, 1.5, 3})},
                 Units{},
                 ""});
  const TallyBook book(two, false);
  EXPECT_TRUE(book.has(Score::exitance, {Coordinate::r, Coordinate::exit_angle}));
  EXPECT_NE(book.offset(Score::exitance, {Coordinate::r, Coordinate::exit_angle}),
            book.offset(Score::exitance, {Coordinate::r}));
}

}  // namespace
}  // namespace scatterlab
