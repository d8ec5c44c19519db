#include "realtime_interposer.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <malloc.h>
#include <pthread.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "archet/realtime_allocations.hpp"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define ARCHET_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define ARCHET_SANITIZER 1
#endif
#endif
#if defined(ARCHET_SANITIZER) && defined(__clang__)
// clang links the sanitizer's runtime, interceptors and all, into the executable: RTLD_NEXT
// would skip them and hide every lock from ThreadSanitizer.
#define ARCHET_SANITIZER_RUNTIME_IN_EXECUTABLE 1
#endif

namespace archet::test {
namespace {

std::atomic<std::uint64_t> counts[static_cast<std::size_t>(RealtimeCall::Count)];
std::atomic<std::uint64_t> sleeps{0};

inline void count(RealtimeCall call) noexcept {
    if (archet::on_realtime_thread())
        counts[static_cast<std::size_t>(call)].fetch_add(1, std::memory_order_relaxed);
}

// The real function `name`, from the objects after this executable in the search order (the
// C library, or a sanitizer's interceptor), looked up once.
thread_local bool resolving = false;  // dlsym may allocate: served from the arena meanwhile

void* next_symbol(std::atomic<void*>& slot, const char* name) noexcept {
    void* f = slot.load(std::memory_order_acquire);
    if (f) return f;
    resolving = true;
    f = ::dlsym(RTLD_NEXT, name);
    resolving = false;
    if (!f) {
        static const char message[] = "realtime_interposer: a real function is missing\n";
        ::syscall(SYS_write, 2, message, sizeof message - 1);
        std::abort();
    }
    slot.store(f, std::memory_order_release);
    return f;
}

#define ARCHET_REAL(name, type)                                                \
    ([]() noexcept {                                                           \
        static std::atomic<void*> slot{nullptr};                               \
        return reinterpret_cast<type>(archet::test::next_symbol(slot, #name)); \
    }())

}  // namespace

const char* name(RealtimeCall call) {
    static const char* const names[] = {"malloc",
                                        "calloc",
                                        "realloc",
                                        "free",
                                        "posix_memalign",
                                        "aligned_alloc",
                                        "memalign",
                                        "valloc/pvalloc",
                                        "allocation (sanitizer hook)",
                                        "free (sanitizer hook)",
                                        "operator new",
                                        "operator delete",
                                        "pthread_mutex_lock",
                                        "pthread_mutex_trylock",
                                        "pthread_mutex_timedlock",
                                        "pthread_mutex_unlock",
                                        "pthread_rwlock_rdlock",
                                        "pthread_rwlock_wrlock",
                                        "pthread_rwlock_unlock",
                                        "pthread_cond_wait",
                                        "pthread_cond_timedwait",
                                        "pthread_cond_signal",
                                        "pthread_cond_broadcast",
                                        "open",
                                        "close",
                                        "read",
                                        "write",
                                        "fopen",
                                        "fclose",
                                        "fread",
                                        "fwrite/fputs/printf/fflush"};
    static_assert(sizeof names / sizeof *names == static_cast<std::size_t>(RealtimeCall::Count));
    return names[static_cast<std::size_t>(call)];
}

std::uint64_t RealtimeCalls::total() const {
    std::uint64_t sum = 0;
    for (auto v : n) sum += v;
    return sum;
}

std::string RealtimeCalls::describe() const {
    std::string s;
    for (std::size_t i = 0; i < n.size(); ++i)
        if (n[i] != 0)
            s += (s.empty() ? "" : ", ") + std::string(name(static_cast<RealtimeCall>(i))) + " " +
                 std::to_string(n[i]);
    return s.empty() ? "none" : s;
}

RealtimeCalls RealtimeCalls::operator-(const RealtimeCalls& before) const {
    RealtimeCalls d;
    for (std::size_t i = 0; i < n.size(); ++i) d.n[i] = n[i] - before.n[i];
    return d;
}

RealtimeCalls realtime_calls() {
    RealtimeCalls c;
    for (std::size_t i = 0; i < c.n.size(); ++i) c.n[i] = counts[i].load(std::memory_order_relaxed);
    c.n[static_cast<std::size_t>(RealtimeCall::OperatorNew)] += archet::realtime_allocations();
    c.n[static_cast<std::size_t>(RealtimeCall::OperatorDelete)] += archet::realtime_deallocations();
    return c;
}

std::uint64_t realtime_sleeps() {
    return sleeps.load(std::memory_order_relaxed);
}

bool c_allocator_interposed_by_name() {
#ifdef ARCHET_SANITIZER
    return false;
#else
    return true;
#endif
}

bool locks_and_io_interposed() {
#ifdef ARCHET_SANITIZER_RUNTIME_IN_EXECUTABLE
    return false;
#else
    return true;
#endif
}

}  // namespace archet::test

using archet::test::count;
using archet::test::RealtimeCall;

// ---- the C allocator ---------------------------------------------------------------------

#ifdef ARCHET_SANITIZER

// The sanitizer's allocator calls these on every allocation and free, whichever function asked.
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));

namespace {
void on_allocation(const volatile void*, std::size_t) {
    count(RealtimeCall::SanitizerAllocation);
}
void on_free(const volatile void*) {
    count(RealtimeCall::SanitizerFree);
}
__attribute__((constructor(101))) void install_sanitizer_hooks() {
    __sanitizer_install_malloc_and_free_hooks(on_allocation, on_free);
}
}  // namespace

#else

namespace {
// What dlsym allocates while the real allocator is being looked up: never freed, never reused.
alignas(std::max_align_t) char arena[64 * 1024];
std::atomic<std::size_t> arena_used{0};
constexpr std::size_t kHeader = alignof(std::max_align_t);

void* arena_allocate(std::size_t size) noexcept {
    const std::size_t rounded = (size + kHeader - 1) / kHeader * kHeader + kHeader;
    const std::size_t at = arena_used.fetch_add(rounded);
    if (at + rounded > sizeof arena) return nullptr;
    std::memcpy(arena + at, &size, sizeof size);
    return arena + at + kHeader;
}
bool in_arena(const void* p) noexcept {
    return p >= static_cast<const void*>(arena) &&
           p < static_cast<const void*>(arena + sizeof arena);
}
}  // namespace

extern "C" {

void* malloc(std::size_t size) __THROW {
    if (archet::test::resolving) return arena_allocate(size);
    count(RealtimeCall::Malloc);
    return ARCHET_REAL(malloc, void* (*)(std::size_t))(size);
}

void* calloc(std::size_t n, std::size_t size) __THROW {
    if (archet::test::resolving) {
        if (size != 0 && n > static_cast<std::size_t>(-1) / size) return nullptr;
        return arena_allocate(n * size);  // static storage: already zero
    }
    count(RealtimeCall::Calloc);
    return ARCHET_REAL(calloc, void* (*)(std::size_t, std::size_t))(n, size);
}

void* realloc(void* p, std::size_t size) __THROW {
    count(RealtimeCall::Realloc);
    if (in_arena(p)) {  // moves out of the arena
        std::size_t old = 0;
        std::memcpy(&old, static_cast<char*>(p) - kHeader, sizeof old);
        void* q = ARCHET_REAL(malloc, void* (*)(std::size_t))(size);
        if (q) std::memcpy(q, p, old < size ? old : size);
        return q;
    }
    return ARCHET_REAL(realloc, void* (*)(void*, std::size_t))(p, size);
}

void free(void* p) __THROW {
    count(RealtimeCall::Free);
    if (in_arena(p)) return;
    ARCHET_REAL(free, void (*)(void*))(p);
}

}  // extern "C"

#endif  // ARCHET_SANITIZER

// ---- the aligned allocations: by name everywhere (a sanitizer's hooks do not see them all)

#ifndef ARCHET_SANITIZER_RUNTIME_IN_EXECUTABLE

extern "C" {

int posix_memalign(void** p, std::size_t alignment, std::size_t size) __THROW {
    count(RealtimeCall::PosixMemalign);
    return ARCHET_REAL(posix_memalign, int (*)(void**, std::size_t, std::size_t))(p, alignment,
                                                                                  size);
}

void* aligned_alloc(std::size_t alignment, std::size_t size) __THROW {
    count(RealtimeCall::AlignedAlloc);
    return ARCHET_REAL(aligned_alloc, void* (*)(std::size_t, std::size_t))(alignment, size);
}

void* memalign(std::size_t alignment, std::size_t size) __THROW {
    count(RealtimeCall::Memalign);
    return ARCHET_REAL(memalign, void* (*)(std::size_t, std::size_t))(alignment, size);
}

void* valloc(std::size_t size) __THROW {
    count(RealtimeCall::Valloc);
    return ARCHET_REAL(valloc, void* (*)(std::size_t))(size);
}

void* pvalloc(std::size_t size) __THROW {
    count(RealtimeCall::Valloc);
    return ARCHET_REAL(pvalloc, void* (*)(std::size_t))(size);
}

}  // extern "C"

#endif  // ARCHET_SANITIZER_RUNTIME_IN_EXECUTABLE

// ---- locks and I/O -----------------------------------------------------------------------

#ifndef ARCHET_SANITIZER_RUNTIME_IN_EXECUTABLE

extern "C" {

int pthread_mutex_lock(pthread_mutex_t* m) __THROWNL {
    count(RealtimeCall::MutexLock);
    return ARCHET_REAL(pthread_mutex_lock, int (*)(pthread_mutex_t*))(m);
}

int pthread_mutex_trylock(pthread_mutex_t* m) __THROWNL {
    count(RealtimeCall::MutexTrylock);
    return ARCHET_REAL(pthread_mutex_trylock, int (*)(pthread_mutex_t*))(m);
}

int pthread_mutex_timedlock(pthread_mutex_t* m, const struct timespec* t) __THROWNL {
    count(RealtimeCall::MutexTimedlock);
    return ARCHET_REAL(pthread_mutex_timedlock, int (*)(pthread_mutex_t*, const timespec*))(m, t);
}

int pthread_mutex_unlock(pthread_mutex_t* m) __THROWNL {
    count(RealtimeCall::MutexUnlock);
    return ARCHET_REAL(pthread_mutex_unlock, int (*)(pthread_mutex_t*))(m);
}

int pthread_mutex_clocklock(pthread_mutex_t* m, clockid_t clock,
                            const struct timespec* t) __THROWNL {
    count(RealtimeCall::MutexTimedlock);
    return ARCHET_REAL(pthread_mutex_clocklock,
                       int (*)(pthread_mutex_t*, clockid_t, const timespec*))(m, clock, t);
}

int pthread_rwlock_rdlock(pthread_rwlock_t* l) __THROWNL {
    count(RealtimeCall::RwlockRead);
    return ARCHET_REAL(pthread_rwlock_rdlock, int (*)(pthread_rwlock_t*))(l);
}

int pthread_rwlock_wrlock(pthread_rwlock_t* l) __THROWNL {
    count(RealtimeCall::RwlockWrite);
    return ARCHET_REAL(pthread_rwlock_wrlock, int (*)(pthread_rwlock_t*))(l);
}

int pthread_rwlock_unlock(pthread_rwlock_t* l) __THROWNL {
    count(RealtimeCall::RwlockUnlock);
    return ARCHET_REAL(pthread_rwlock_unlock, int (*)(pthread_rwlock_t*))(l);
}

int pthread_cond_wait(pthread_cond_t* c, pthread_mutex_t* m) {
    count(RealtimeCall::CondWait);
    return ARCHET_REAL(pthread_cond_wait, int (*)(pthread_cond_t*, pthread_mutex_t*))(c, m);
}

int pthread_cond_timedwait(pthread_cond_t* c, pthread_mutex_t* m, const struct timespec* t) {
    count(RealtimeCall::CondTimedwait);
    return ARCHET_REAL(pthread_cond_timedwait,
                       int (*)(pthread_cond_t*, pthread_mutex_t*, const timespec*))(c, m, t);
}

int pthread_cond_clockwait(pthread_cond_t* c, pthread_mutex_t* m, clockid_t clock,
                           const struct timespec* t) {
    count(RealtimeCall::CondTimedwait);
    return ARCHET_REAL(pthread_cond_clockwait, int (*)(pthread_cond_t*, pthread_mutex_t*, clockid_t,
                                                       const timespec*))(c, m, clock, t);
}

int pthread_cond_signal(pthread_cond_t* c) __THROWNL {
    count(RealtimeCall::CondSignal);
    return ARCHET_REAL(pthread_cond_signal, int (*)(pthread_cond_t*))(c);
}

int pthread_cond_broadcast(pthread_cond_t* c) __THROWNL {
    count(RealtimeCall::CondBroadcast);
    return ARCHET_REAL(pthread_cond_broadcast, int (*)(pthread_cond_t*))(c);
}

// Not a forbidden call: the null sink's thread waits for its next block in it. Counted apart,
// as the proof that the engine's real-time thread is marked and seen.
int clock_nanosleep(clockid_t clock, int flags, const struct timespec* t, struct timespec* left) {
    if (archet::on_realtime_thread()) archet::test::sleeps.fetch_add(1, std::memory_order_relaxed);
    return ARCHET_REAL(clock_nanosleep, int (*)(clockid_t, int, const timespec*, timespec*))(
        clock, flags, t, left);
}

// open's mode is there only when the flags create a file.
static mode_t mode_of(int flags, va_list& more) {
    return (flags & O_CREAT) || (flags & O_TMPFILE) == O_TMPFILE ? va_arg(more, mode_t) : 0;
}

int open(const char* path, int flags, ...) {
    count(RealtimeCall::Open);
    va_list more;
    va_start(more, flags);
    const mode_t mode = mode_of(flags, more);
    va_end(more);
    return ARCHET_REAL(open, int (*)(const char*, int, ...))(path, flags, mode);
}

int open64(const char* path, int flags, ...) {
    count(RealtimeCall::Open);
    va_list more;
    va_start(more, flags);
    const mode_t mode = mode_of(flags, more);
    va_end(more);
    return ARCHET_REAL(open64, int (*)(const char*, int, ...))(path, flags, mode);
}

int openat(int dir, const char* path, int flags, ...) {
    count(RealtimeCall::Open);
    va_list more;
    va_start(more, flags);
    const mode_t mode = mode_of(flags, more);
    va_end(more);
    return ARCHET_REAL(openat, int (*)(int, const char*, int, ...))(dir, path, flags, mode);
}

int creat(const char* path, mode_t mode) {
    count(RealtimeCall::Open);
    return ARCHET_REAL(creat, int (*)(const char*, mode_t))(path, mode);
}

int close(int fd) {
    count(RealtimeCall::Close);
    return ARCHET_REAL(close, int (*)(int))(fd);
}

ssize_t read(int fd, void* to, std::size_t n) {
    count(RealtimeCall::Read);
    return ARCHET_REAL(read, ssize_t(*)(int, void*, std::size_t))(fd, to, n);
}

ssize_t pread(int fd, void* to, std::size_t n, off_t at) {
    count(RealtimeCall::Read);
    return ARCHET_REAL(pread, ssize_t(*)(int, void*, std::size_t, off_t))(fd, to, n, at);
}

ssize_t write(int fd, const void* from, std::size_t n) {
    count(RealtimeCall::Write);
    return ARCHET_REAL(write, ssize_t(*)(int, const void*, std::size_t))(fd, from, n);
}

ssize_t pwrite(int fd, const void* from, std::size_t n, off_t at) {
    count(RealtimeCall::Write);
    return ARCHET_REAL(pwrite, ssize_t(*)(int, const void*, std::size_t, off_t))(fd, from, n, at);
}

FILE* fopen(const char* path, const char* mode) {
    count(RealtimeCall::Fopen);
    return ARCHET_REAL(fopen, FILE * (*)(const char*, const char*))(path, mode);
}

FILE* fopen64(const char* path, const char* mode) {
    count(RealtimeCall::Fopen);
    return ARCHET_REAL(fopen64, FILE * (*)(const char*, const char*))(path, mode);
}

FILE* fdopen(int fd, const char* mode) __THROW {
    count(RealtimeCall::Fopen);
    return ARCHET_REAL(fdopen, FILE * (*)(int, const char*))(fd, mode);
}

int fclose(FILE* f) {
    count(RealtimeCall::Fclose);
    return ARCHET_REAL(fclose, int (*)(FILE*))(f);
}

std::size_t fread(void* to, std::size_t size, std::size_t n, FILE* f) {
    count(RealtimeCall::Fread);
    return ARCHET_REAL(fread, std::size_t(*)(void*, std::size_t, std::size_t, FILE*))(to, size, n,
                                                                                      f);
}

std::size_t fwrite(const void* from, std::size_t size, std::size_t n, FILE* f) {
    count(RealtimeCall::Fwrite);
    return ARCHET_REAL(fwrite, std::size_t(*)(const void*, std::size_t, std::size_t, FILE*))(
        from, size, n, f);
}

int fputs(const char* s, FILE* f) {
    count(RealtimeCall::Fwrite);
    return ARCHET_REAL(fputs, int (*)(const char*, FILE*))(s, f);
}

int puts(const char* s) {
    count(RealtimeCall::Fwrite);
    return ARCHET_REAL(puts, int (*)(const char*))(s);
}

int fputc(int c, FILE* f) {
    count(RealtimeCall::Fwrite);
    return ARCHET_REAL(fputc, int (*)(int, FILE*))(c, f);
}

int fflush(FILE* f) {
    count(RealtimeCall::Fwrite);
    return ARCHET_REAL(fflush, int (*)(FILE*))(f);
}

int vfprintf(FILE* f, const char* format, va_list arguments) {
    count(RealtimeCall::Fwrite);
    return ARCHET_REAL(vfprintf, int (*)(FILE*, const char*, va_list))(f, format, arguments);
}

int fprintf(FILE* f, const char* format, ...) {
    count(RealtimeCall::Fwrite);
    va_list arguments;
    va_start(arguments, format);
    const int n = ARCHET_REAL(vfprintf, int (*)(FILE*, const char*, va_list))(f, format, arguments);
    va_end(arguments);
    return n;
}

int printf(const char* format, ...) {
    count(RealtimeCall::Fwrite);
    va_list arguments;
    va_start(arguments, format);
    const int n =
        ARCHET_REAL(vfprintf, int (*)(FILE*, const char*, va_list))(stdout, format, arguments);
    va_end(arguments);
    return n;
}

}  // extern "C"

#endif  // ARCHET_SANITIZER_RUNTIME_IN_EXECUTABLE
