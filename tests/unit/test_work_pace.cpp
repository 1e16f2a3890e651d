// The rate and time left of work resumed from an earlier process count this process's work only.
#include <gtest/gtest.h>

#include <cmath>

#include "scatterlab/core/work_pace.hpp"

namespace scatterlab {
namespace {

TEST(WorkPace, FreshRunExtrapolatesItsOwnRate) {
  const WorkPace pace{16, 64, 0, 8.0};  // 16 batches in 8 s
  EXPECT_DOUBLE_EQ(pace.units_per_second(), 2.0);
  EXPECT_DOUBLE_EQ(pace.seconds_left(), 24.0);  // 48 more at 2 per second
}

TEST(WorkPace, ResumedWorkIsNeitherFastNorSlow) {
  // 32 of 64 were done before this process; it has done 8 in 4 s. Counting the resumed batches
  // as its own would give 40 / 4 = 10 per second and 2.4 s left, not 12 s.
  const WorkPace pace{40, 64, 32, 4.0};
  EXPECT_DOUBLE_EQ(pace.units_per_second(), 2.0);
  EXPECT_DOUBLE_EQ(pace.seconds_left(), 12.0);
}

TEST(WorkPace, NoRateBeforeAnyWorkOrTime) {
  EXPECT_TRUE(std::isnan(WorkPace{32, 64, 32, 5.0}.seconds_left()));
  EXPECT_TRUE(std::isnan(WorkPace{0, 64, 0, 0.0}.units_per_second()));
  EXPECT_DOUBLE_EQ((WorkPace{64, 64, 32, 5.0}.seconds_left()), 0.0);
}

TEST(WorkPace, DurationsReadAtTheirScale) {
  EXPECT_EQ(duration_text(41.2), "41 s");
  EXPECT_EQ(duration_text(180.0), "3 min");
  EXPECT_EQ(duration_text(9000.0), "2.5 h");
  EXPECT_EQ(duration_text(std::nan("")), "--");
}

}  // namespace
}  // namespace scatterlab
