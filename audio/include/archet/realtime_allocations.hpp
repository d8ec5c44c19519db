#pragma once
// Proof that real-time threads do not allocate: every operator new and operator delete in the
// process (all forms: plain, array, sized, aligned, nothrow) checks whether its thread has
// declared itself real-time, and counts it if so. The engine reports the count in its status
// frames; the tests expect zero. (tests/realtime_interposer.hpp counts the C allocator, locks
// and I/O on the same marked threads.)

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

/// Whether the calling thread is marked real-time now. Allocation-free and lock-free: an
/// interposed malloc may ask it.
bool on_realtime_thread() noexcept;

/// Calls of operator new (any form) made so far on threads while they were marked real-time.
std::uint64_t realtime_allocations();

/// Calls of operator delete (any form, null pointers included) made so far on marked threads.
std::uint64_t realtime_deallocations();

}  // namespace archet
