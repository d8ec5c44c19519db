#pragma once
// Proof that real-time threads do not allocate: every operator new and operator delete in the
// process (all forms: plain, array, sized, aligned, nothrow) checks whether its thread has
// declared itself real-time, and counts it if so. The engine reports the count in its status
// frames; the tests expect zero. (tests/support/realtime_interposer.hpp counts the C allocator,
// locks and I/O on the same marked threads.) The replacement is its own library,
// archet_realtime_allocations, linked by the engine and the `archet` command only: the studio
// keeps the standard allocator.

#include <cstdint>

#include "archet/realtime_thread_mark.hpp"

namespace archet {

/// Calls of operator new (any form) made so far on threads while they were marked real-time.
std::uint64_t realtime_allocations();

/// Calls of operator delete (any form, null pointers included) made so far on marked threads.
std::uint64_t realtime_deallocations();

}  // namespace archet
