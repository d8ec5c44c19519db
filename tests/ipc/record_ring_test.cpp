// The ring of records whose length is chosen when it is made (a take's samples, one value for
// each of the model's probes): order and every value across two threads, drop-and-count when
// full, and a length or capacity it cannot hold refused.

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>

#include "archet/ipc/record_ring.hpp"

namespace archet::ipc {
namespace {

double value_of(std::uint64_t record, std::size_t column) {  // a distinct value for each
    return static_cast<double>(record) * 1000.0 + static_cast<double>(column);
}

TEST(RecordRing, AFullRingDropsAndCountsWithoutBlocking) {
    RecordRing ring(3, 4);
    for (int i = 0; i < 4; ++i) {
        double* r = ring.claim();
        ASSERT_NE(r, nullptr);
        r[0] = i;
        ring.publish();
    }
    EXPECT_EQ(ring.claim(), nullptr);
    EXPECT_EQ(ring.claim(), nullptr);
    EXPECT_EQ(ring.dropped(), 2u);
    for (int i = 0; i < 4; ++i) {
        const double* r = ring.front();
        ASSERT_NE(r, nullptr);
        EXPECT_EQ(r[0], i);
        ring.release();
    }
    EXPECT_EQ(ring.front(), nullptr);
    EXPECT_NE(ring.claim(), nullptr) << "room again once read";
}

// Records longer than any fixed frame (ipc::kMaxProbes values), of a length given at run time.
TEST(RecordRing, TwoThreadsKeepOrderAndEveryValue) {
    constexpr std::size_t kLength = 2 + kMaxProbes + 7;
    constexpr std::uint64_t kRecords = 300000;
    RecordRing ring(kLength, 64);
    ASSERT_EQ(ring.length(), kLength);
    std::thread producer([&] {
        for (std::uint64_t i = 0; i < kRecords;) {
            double* r = ring.claim();
            if (!r) continue;
            for (std::size_t c = 0; c < kLength; ++c) r[c] = value_of(i, c);
            ring.publish();
            ++i;
        }
    });
    std::uint64_t expected = 0;
    bool intact = true;
    while (expected < kRecords) {
        const double* r = ring.front();
        if (!r) continue;
        for (std::size_t c = 0; c < kLength; ++c) intact = intact && r[c] == value_of(expected, c);
        ring.release();
        ++expected;
    }
    producer.join();
    EXPECT_TRUE(intact) << "a record arrived torn or out of order";
    EXPECT_EQ(ring.front(), nullptr);
}

TEST(RecordRing, RefusesEmptyRecordsAndACapacityNotAPowerOfTwo) {
    EXPECT_THROW(RecordRing(0, 8), std::invalid_argument);
    EXPECT_THROW(RecordRing(4, 0), std::invalid_argument);
    EXPECT_THROW(RecordRing(4, 6), std::invalid_argument);
    EXPECT_EQ(RecordRing(4, 8).capacity(), 8u);
}

}  // namespace
}  // namespace archet::ipc
