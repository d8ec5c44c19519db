// The lock-free rings and the segment layout: order and integrity across threads and across
// two real processes, drop-and-count when full, and every corrupt layout refused.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <random>
#include <thread>

#include "archet/ipc/shared_segment.hpp"

namespace archet::ipc {
namespace {

std::uint64_t scramble(std::uint64_t x) {  // a checksum for each frame's payload
    x ^= x >> 33, x *= 0xff51afd7ed558ccdULL, x ^= x >> 33;
    return x;
}

TEST(SpscRing, AFullRingDropsAndCountsWithoutBlocking) {
    LocalRing<CommandFrame> local(8);
    auto& ring = local.ring();
    CommandFrame f{};
    for (int i = 0; i < 8; ++i) EXPECT_TRUE(ring.try_push(f));
    EXPECT_FALSE(ring.try_push(f));
    EXPECT_FALSE(ring.try_push(f));
    EXPECT_EQ(ring.dropped(), 2u);
    EXPECT_EQ(ring.waiting(), 8u);
    for (int i = 0; i < 8; ++i) EXPECT_TRUE(ring.try_pop(f));
    EXPECT_FALSE(ring.try_pop(f));
}

TEST(SpscRing, TwoThreadsKeepOrderAndData) {
    LocalRing<ProbeFrame> local(64);
    auto& ring = local.ring();
    constexpr std::uint64_t kFrames = 500000;
    std::thread producer([&] {
        for (std::uint64_t i = 0; i < kFrames;) {
            ProbeFrame f{};
            f.tick = i;
            f.values[3] = static_cast<double>(scramble(i) % 1000003);
            if (ring.try_push(f)) ++i;
        }
    });
    std::uint64_t expected = 0;
    ProbeFrame f;
    while (expected < kFrames)
        if (ring.try_pop(f)) {
            ASSERT_EQ(f.tick, expected);
            ASSERT_EQ(f.values[3], static_cast<double>(scramble(expected) % 1000003));
            ++expected;
        }
    producer.join();
}

TEST(SpscRing, TwoProcessesThroughSharedMemoryRandomised) {
    SharedSegment segment = SharedSegment::create(plan_layout(16, 2, 2, 2));
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    constexpr std::uint32_t kFrames = 200000;
    if (child == 0) {  // the producer: another process, attaching by name like the engine
        SharedSegment mine = SharedSegment::attach(segment.name());
        auto ring = mine.commands();
        std::mt19937 random(42);
        for (std::uint32_t i = 0; i < kFrames;) {
            CommandFrame f{};
            f.sequence = i;
            f.value = static_cast<double>(scramble(i));
            const auto length = random() % (kTextSize - 1);
            for (std::size_t c = 0; c < length; ++c)
                f.text[c] = static_cast<char>('a' + (i + c) % 26);
            if (ring.try_push(f)) ++i;
            if (random() % 1000 == 0) ::usleep(200);  // uneven pace
        }
        ::_exit(0);
    }
    auto ring = segment.commands();
    std::uint32_t expected = 0;
    CommandFrame f;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (expected < kFrames && std::chrono::steady_clock::now() < deadline) {
        if (!ring.try_pop(f)) continue;
        ASSERT_EQ(f.sequence, expected);
        ASSERT_EQ(f.value, static_cast<double>(scramble(expected)));
        for (std::size_t c = 0; f.text[c]; ++c)
            ASSERT_EQ(f.text[c], static_cast<char>('a' + (expected + c) % 26));
        ++expected;
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_EQ(expected, kFrames);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST(SegmentLayout, EveryCorruptFieldIsRefused) {
    const Layout good = plan_layout(256, 1 << 16, 64, 256);
    ASSERT_EQ(validate_layout(good, good.segment_size), nullptr);
    struct Case {
        const char* what;
        void (*corrupt)(Layout&);
    };
    const Case cases[] = {
        {"bad magic", [](Layout& l) { l.magic = 0x12345678; }},
        {"segment needs a newer engine", [](Layout& l) { l.minimum_compatible_version = 99; }},
        {"header size", [](Layout& l) { l.header_size += 8; }},
        {"segment size", [](Layout& l) { l.segment_size += 64; }},
        {"frame size", [](Layout& l) { l.probes.frame_size = 8; }},
        {"power of two", [](Layout& l) { l.commands.capacity = 100; }},
        {"power of two", [](Layout& l) { l.status.capacity = 0; }},
        {"not aligned", [](Layout& l) { l.shapes.offset += 8; }},
        {"overlaps the header", [](Layout& l) { l.commands.offset = 0; }},
        {"runs past", [](Layout& l) { l.status.offset = l.segment_size - 64; }},
        {"runs past", [](Layout& l) { l.probes.offset = ~0ULL & ~63ULL; }},
        {"overlap", [](Layout& l) { l.shapes.offset = l.probes.offset; }},
    };
    for (const auto& c : cases) {
        Layout bad = good;
        c.corrupt(bad);
        const std::uint64_t mapped = good.segment_size;
        const char* problem = validate_layout(bad, mapped);
        ASSERT_NE(problem, nullptr) << c.what;
        EXPECT_NE(std::string(problem).find(c.what), std::string::npos) << problem;
    }
}

TEST(SegmentLayout, ACorruptCountIsResetNotTrusted) {
    SharedSegment segment = SharedSegment::create(plan_layout(8, 2, 2, 2));
    auto commands = segment.commands();
    CommandFrame f{};
    commands.try_push(f);
    // A hostile writer claims a billion frames are waiting.
    auto* rc = reinterpret_cast<RingControl*>(static_cast<char*>(segment.base()) +
                                              segment.header().commands.offset);
    rc->written.store(1'000'000'000);
    EXPECT_FALSE(commands.try_pop(f));
    EXPECT_EQ(commands.waiting(), 0u) << "the consumer resynchronised";
}

}  // namespace
}  // namespace archet::ipc
