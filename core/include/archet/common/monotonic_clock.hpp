#pragma once
// Nanoseconds on the monotonic clock, for timing callbacks and device I/O. clock_gettime reads
// it through the vDSO without a system call, so real-time threads may use it.

#include <time.h>

#include <cstdint>

namespace archet {

inline std::int64_t monotonic_ns() {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

}  // namespace archet
