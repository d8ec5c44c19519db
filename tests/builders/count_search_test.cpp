// The full-bandwidth builder's search for its mass count starts where a cheap estimate says,
// and must still find what a search from the top finds: checked against every edge an exact
// test can have and estimates that are right, too cautious or too bold near it.

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "archet/builders/count_search.hpp"

namespace archet {
namespace {

constexpr int kLow = 20, kHigh = 40;

// What the builder's loop finds from `start`: the first count down that keeps the reserve.
int first_kept_from(int start, int edge) {
    for (int n = start; n > kLow; --n)
        if (n <= edge) return n;
    return kLow;
}

TEST(CountSearch, FindsWhatASearchFromTheTopFindsWhereverTheEstimateErs) {
    // The exact test keeps every count up to `edge`; the estimate keeps up to `edge + error`.
    for (int edge = kLow - 1; edge <= kHigh; ++edge)
        for (int error = -6; error <= 6; ++error) {
            std::set<int> exact_calls;
            const int start = count_search_start(
                kLow, kHigh, [&](int n) { return n <= edge + error; },
                [&](int n) {
                    exact_calls.insert(n);
                    return n <= edge;
                });
            SCOPED_TRACE("edge " + std::to_string(edge) + ", estimate off by " +
                         std::to_string(error));
            ASSERT_GE(start, kLow);
            ASSERT_LE(start, kHigh);
            // Every count above the start lacks the reserve, and so does the start unless it
            // is the top: the search down from it is the search from the top.
            EXPECT_TRUE(start == kHigh || start > edge);
            EXPECT_EQ(first_kept_from(start, edge), first_kept_from(kHigh, edge));
            // The exact test is asked of no count below the estimate's edge, and of few above.
            for (int n : exact_calls) EXPECT_GT(n, std::min(edge, edge + error));
            EXPECT_LE(exact_calls.size(), static_cast<std::size_t>(std::max(0, -error) + 1));
        }
}

TEST(CountSearch, AnEstimateThatKeepsTheTopStartsThereWithoutTheExactTest) {
    bool asked = false;
    const int start = count_search_start(
        kLow, kHigh, [](int) { return true; },
        [&](int) {
            asked = true;
            return true;
        });
    EXPECT_EQ(start, kHigh);
    EXPECT_FALSE(asked);
}

TEST(CountSearch, ACancelStopsTheExactTests) {
    int exact = 0;
    EXPECT_THROW(count_search_start(
                     kLow, kHigh, [](int n) { return n <= kLow + 1; },
                     [&](int) {
                         ++exact;
                         return true;
                     },
                     [&] {
                         if (exact == 2) throw std::runtime_error("cancelled");
                     }),
                 std::runtime_error);
    EXPECT_EQ(exact, 2);
}

TEST(CountSearch, OneCountIsItsOwnStart) {
    EXPECT_EQ(count_search_start(
                  kLow, kLow, [](int) { return false; }, [](int) { return false; }),
              kLow);
}

TEST(CountSearch, ACancelStopsTheEstimates) {
    int estimates = 0;
    EXPECT_THROW(count_search_start(
                     kLow, kHigh,
                     [&](int) {
                         ++estimates;
                         return false;
                     },
                     [](int) { return false; },
                     [&] {
                         if (estimates == 3) throw std::runtime_error("cancelled");
                     }),
                 std::runtime_error);
    EXPECT_EQ(estimates, 3);
}

}  // namespace
}  // namespace archet
