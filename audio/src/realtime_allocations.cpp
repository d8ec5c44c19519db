#include "archet/realtime_allocations.hpp"

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace {
using archet::on_realtime_thread;
std::atomic<std::uint64_t> allocated{0}, deallocated{0};

void* try_allocate(std::size_t size, std::size_t alignment) noexcept {
    if (on_realtime_thread()) allocated.fetch_add(1, std::memory_order_relaxed);
    if (size == 0) size = 1;
    return alignment > alignof(std::max_align_t)
               ? std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment)
               : std::malloc(size);
}

void* allocate(std::size_t size, std::size_t alignment) {
    if (void* p = try_allocate(size, alignment)) return p;
    throw std::bad_alloc();
}

void deallocate(void* p) noexcept {
    if (on_realtime_thread()) deallocated.fetch_add(1, std::memory_order_relaxed);
    std::free(p);
}
}  // namespace

// Replacements of the global allocation functions, linked into the programs that run the
// engine or `archet play` (not the studio). They behave as the standard ones apart from the count.
void* operator new(std::size_t size) {
    return allocate(size, 0);
}
void* operator new[](std::size_t size) {
    return allocate(size, 0);
}
void* operator new(std::size_t size, std::align_val_t a) {
    return allocate(size, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t size, std::align_val_t a) {
    return allocate(size, static_cast<std::size_t>(a));
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    return try_allocate(size, 0);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    return try_allocate(size, 0);
}
void* operator new(std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
    return try_allocate(size, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
    return try_allocate(size, static_cast<std::size_t>(a));
}
void operator delete(void* p) noexcept {
    deallocate(p);
}
void operator delete[](void* p) noexcept {
    deallocate(p);
}
void operator delete(void* p, std::size_t) noexcept {
    deallocate(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    deallocate(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
    deallocate(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
    deallocate(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
    deallocate(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
    deallocate(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
    deallocate(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
    deallocate(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
    deallocate(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
    deallocate(p);
}

namespace archet {

std::uint64_t realtime_allocations() {
    return allocated.load(std::memory_order_relaxed);
}
std::uint64_t realtime_deallocations() {
    return deallocated.load(std::memory_order_relaxed);
}

}  // namespace archet
