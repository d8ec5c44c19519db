#pragma once
// Which threads are real-time: the audio outputs mark their callback threads, and the counting
// allocator (realtime_allocations.hpp) and the tests' interposer judge by the mark. Marking is a
// thread-local flag and nothing else, so a program without the counting allocator (the studio,
// whose preview player plays through these outputs) pays nothing for it.

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

}  // namespace archet
