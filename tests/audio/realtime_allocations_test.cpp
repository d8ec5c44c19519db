// The counter behind the engine's "no allocation on the real-time thread" proof counts what
// it should: allocations on marked threads, and nothing else.

#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

#include "archet/realtime_allocations.hpp"

namespace archet {
namespace {

TEST(RealtimeAllocations, CountsOnlyOnMarkedThreads) {
    const auto before = realtime_allocations();
    auto unmarked = std::make_unique<std::vector<int>>(100);
    EXPECT_EQ(realtime_allocations(), before);
    std::thread([] {
        const RealtimeThreadMark mark;
        auto p = std::make_unique<int>(1);
        std::vector<double> v(10);
        (void)p;
    }).join();
    EXPECT_EQ(realtime_allocations(), before + 2);
    auto after = std::make_unique<int>(2);
    EXPECT_EQ(realtime_allocations(), before + 2) << "the mark ends with its scope";
}

}  // namespace
}  // namespace archet
