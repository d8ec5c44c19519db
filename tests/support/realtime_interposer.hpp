#pragma once
// Counts, on threads marked real-time (archet/realtime_allocations.hpp), every call a real-time
// thread must not make: the C allocator (malloc, calloc, realloc, free, posix_memalign,
// aligned_alloc, memalign, valloc, pvalloc), operator new and delete in every form, the pthread
// mutex, rwlock and condition-variable calls, and the I/O wrappers (open, read, write, close,
// fopen, fwrite, fputs, printf, ...). Linked into a test executable, its definitions interpose
// the C library's for the whole process and forward to the real ones (dlsym(RTLD_NEXT)).
//
// Under AddressSanitizer or ThreadSanitizer the sanitizer owns malloc: malloc, calloc, realloc
// and free are then counted through the sanitizer's own allocation hooks (every allocation and
// every free, without telling malloc from calloc); the aligned allocations (which those hooks do
// not all see), the pthread and the I/O calls are interposed by name as without one, and
// forwarded to the sanitizer's interceptors, which come next after the executable (GCC links
// its sanitizer runtimes as shared libraries, first in the search order).

#include <array>
#include <cstdint>
#include <string>

namespace archet::test {

enum class RealtimeCall : int {
    Malloc,
    Calloc,
    Realloc,
    Free,
    PosixMemalign,
    AlignedAlloc,
    Memalign,
    Valloc,
    SanitizerAllocation,  ///< under a sanitizer: any allocation its allocator made
    SanitizerFree,        ///< under a sanitizer: any free
    OperatorNew,          ///< every form (archet/realtime_allocations.hpp counts them)
    OperatorDelete,       ///< every form
    MutexLock,
    MutexTrylock,
    MutexTimedlock,  ///< pthread_mutex_timedlock, pthread_mutex_clocklock
    MutexUnlock,
    RwlockRead,
    RwlockWrite,
    RwlockUnlock,
    CondWait,
    CondTimedwait,  ///< pthread_cond_timedwait, pthread_cond_clockwait
    CondSignal,
    CondBroadcast,
    Open,  ///< open, open64, openat, creat
    Close,
    Read,   ///< read, pread
    Write,  ///< write, pwrite
    Fopen,  ///< fopen, fopen64, fdopen
    Fclose,
    Fread,
    Fwrite,  ///< fwrite, fputs, puts, fputc, printf, fprintf, vfprintf, fflush
    Count
};

const char* name(RealtimeCall call);

/// Calls counted so far, by kind.
struct RealtimeCalls {
    std::array<std::uint64_t, static_cast<std::size_t>(RealtimeCall::Count)> n{};
    std::uint64_t operator[](RealtimeCall c) const { return n[static_cast<std::size_t>(c)]; }
    std::uint64_t total() const;
    /// "malloc 3, pthread_mutex_lock 1" (the kinds that are not zero), or "none".
    std::string describe() const;
    RealtimeCalls operator-(const RealtimeCalls& before) const;
};

RealtimeCalls realtime_calls();

/// clock_nanosleep calls on marked threads: allowed (the null sink's thread waits for its next
/// block in it), and so a witness that a real-time thread was marked and its calls seen.
std::uint64_t realtime_sleeps();

/// Whether malloc, calloc, realloc and free are interposed by name (false under a sanitizer:
/// then they are counted as SanitizerAllocation and SanitizerFree).
bool c_allocator_interposed_by_name();

/// Whether the pthread and I/O calls are interposed (false where a sanitizer's runtime is linked
/// into the executable itself, as clang does: forwarding would bypass its interceptors).
bool locks_and_io_interposed();

}  // namespace archet::test
