// parallel_for: every piece runs once whatever the number of threads, a piece's exception
// reaches the caller, and a cancel stops handing out pieces.

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "archet/common/parallel_for.hpp"

namespace archet {
namespace {

TEST(ParallelFor, RunsEveryPieceOnceOnAnyNumberOfThreads) {
    for (int jobs : {1, 2, 7}) {
        std::vector<int> runs(101, 0);
        std::vector<std::size_t> reported;
        EXPECT_TRUE(parallel_for(
            runs.size(), jobs, [&](std::size_t i) { ++runs[i]; }, nullptr,
            [&](std::size_t done, std::size_t total) {
                EXPECT_EQ(total, runs.size());
                reported.push_back(done);
            }));
        for (int r : runs) EXPECT_EQ(r, 1) << jobs << " threads";
        ASSERT_FALSE(reported.empty());
        EXPECT_EQ(reported.back(), runs.size()) << "the last report is the whole";
    }
    EXPECT_TRUE(parallel_for(0, 2, [](std::size_t) { FAIL() << "no piece to run"; }));
}

TEST(ParallelFor, APiecesExceptionReachesTheCaller) {
    std::atomic<int> ran{0};
    EXPECT_THROW(parallel_for(50, 1,
                              [&](std::size_t i) {
                                  ++ran;
                                  if (i == 3) throw std::runtime_error("piece 3");
                              }),
                 std::runtime_error);
    EXPECT_EQ(ran.load(), 4) << "no piece is handed out after one failed";
    EXPECT_THROW(parallel_for(50, 2,
                              [](std::size_t i) {
                                  if (i % 7 == 3) throw std::runtime_error("piece");
                              }),
                 std::runtime_error)
        << "on several threads too";
}

TEST(ParallelFor, ACancelStopsHandingOutPieces) {
    std::atomic<bool> cancel{false};
    std::atomic<int> ran{0};
    EXPECT_FALSE(parallel_for(
        1000, 1,
        [&](std::size_t) {
            if (++ran == 10) cancel.store(true);
        },
        &cancel));
    EXPECT_EQ(ran.load(), 10);
}

}  // namespace
}  // namespace archet
