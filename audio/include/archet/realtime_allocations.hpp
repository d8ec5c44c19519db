#pragma once
// Proof that real-time threads do not allocate: every operator new in the process checks
// whether its thread has declared itself real-time, and counts it if so. The engine reports
// the count in its status frames; the tests expect zero.

#include <cstdint>

namespace archet {

/// Marks the calling thread as real-time for the guard's lifetime.
class RealtimeThreadMark {
  public:
    RealtimeThreadMark();
    ~RealtimeThreadMark();
    RealtimeThreadMark(const RealtimeThreadMark&) = delete;
    RealtimeThreadMark& operator=(const RealtimeThreadMark&) = delete;
};

/// Marks the calling thread real-time for good (audio callbacks whose thread the driver owns).
void mark_realtime_thread();

/// Allocations made so far on threads while they were marked real-time.
std::uint64_t realtime_allocations();

}  // namespace archet
