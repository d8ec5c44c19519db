// Which of a string's points a drawing of at most so many shows: every one when they fit, else
// that many spread evenly from the first to the last, in order and none twice.

#include <gtest/gtest.h>

#include <numeric>

#include "archet/model/string_points.hpp"

namespace archet {
namespace {

TEST(DrawnPoints, AStringThatFitsIsDrawnWhole) {
    std::vector<std::size_t> all(62);
    std::iota(all.begin(), all.end(), std::size_t{0});
    EXPECT_EQ(drawn_points(62, 512), all);
    all.resize(512);
    std::iota(all.begin(), all.end(), std::size_t{0});
    EXPECT_EQ(drawn_points(512, 512), all);
}

TEST(DrawnPoints, ALongerStringIsDrawnFromEndToEndInEvenSteps) {
    for (std::size_t points : {513u, 602u, 1002u, 10002u, 500002u}) {
        const std::vector<std::size_t> drawn = drawn_points(points, 512);
        ASSERT_EQ(drawn.size(), 512u) << points;
        EXPECT_EQ(drawn.front(), 0u) << points;
        EXPECT_EQ(drawn.back(), points - 1) << "the far end: " << points;
        const double step = static_cast<double>(points - 1) / 511;
        for (std::size_t i = 1; i < drawn.size(); ++i) {
            ASSERT_GT(drawn[i], drawn[i - 1]) << points << " at " << i;
            EXPECT_LE(std::abs(static_cast<double>(drawn[i]) - step * static_cast<double>(i)), 0.5)
                << points << " at " << i << ": the nearest point to an even step";
        }
    }
}

TEST(DrawnPoints, NoRoomDrawsTheFirstPointsThatFit) {
    EXPECT_TRUE(drawn_points(10, 0).empty());
    EXPECT_EQ(drawn_points(10, 1), std::vector<std::size_t>{0});
    EXPECT_TRUE(drawn_points(0, 512).empty());
}

}  // namespace
}  // namespace archet
