#pragma once
// A single-producer/single-consumer ring of fixed-size plain-data frames, living in memory
// that may be shared between processes (the control block and the frames sit at offsets in
// the segment). Never blocks and never allocates: a full ring drops the frame and counts it.
// Acquire/release on the monotonic indices orders the frame data.

#include <cstdint>
#include <cstring>
#include <new>
#include <type_traits>

#include "archet/ipc/segment_layout.hpp"

namespace archet::ipc {

template <class Frame>
class SpscRing {
    static_assert(std::is_trivially_copyable_v<Frame>);

  public:
    SpscRing() = default;
    /// `base` is the segment start; the descriptor has been validated for this Frame.
    SpscRing(void* base, const RingDescriptor& d)
        : control_(reinterpret_cast<RingControl*>(static_cast<char*>(base) + d.offset)),
          frames_(
              reinterpret_cast<Frame*>(static_cast<char*>(base) + d.offset + sizeof(RingControl))),
          mask_(d.capacity - 1) {}

    /// Producer: copies the frame in; false (and counted) when the ring is full.
    bool try_push(const Frame& frame) {
        const std::uint64_t w = control_->written.load(std::memory_order_relaxed);
        const std::uint64_t r = control_->read.load(std::memory_order_acquire);
        if (w - r > mask_) {
            control_->dropped.fetch_add(1, std::memory_order_relaxed);
            return false;
        }
        std::memcpy(&frames_[w & mask_], &frame, sizeof(Frame));
        control_->written.store(w + 1, std::memory_order_release);
        return true;
    }

    /// Consumer: copies the oldest frame out; false when empty. A count that makes no sense
    /// (a corrupt or hostile producer) is reset to empty rather than trusted.
    bool try_pop(Frame& frame) {
        const std::uint64_t r = control_->read.load(std::memory_order_relaxed);
        const std::uint64_t w = control_->written.load(std::memory_order_acquire);
        if (w == r) return false;
        if (w - r > mask_ + 1) {
            control_->read.store(w, std::memory_order_release);
            return false;
        }
        std::memcpy(&frame, &frames_[r & mask_], sizeof(Frame));
        control_->read.store(r + 1, std::memory_order_release);
        return true;
    }

    std::uint64_t waiting() const {
        return control_->written.load(std::memory_order_acquire) -
               control_->read.load(std::memory_order_acquire);
    }
    std::uint64_t dropped() const { return control_->dropped.load(std::memory_order_relaxed); }
    std::uint32_t capacity() const { return mask_ + 1; }

  private:
    RingControl* control_ = nullptr;
    Frame* frames_ = nullptr;
    std::uint32_t mask_ = 0;
};

/// The same ring in this process's own memory, for handing work between threads.
template <class Frame>
class LocalRing {
  public:
    explicit LocalRing(std::uint32_t capacity)
        : memory_(static_cast<char*>(::operator new (sizeof(RingControl) + sizeof(Frame) * capacity,
                                                     std::align_val_t{64}))) {
        new (memory_) RingControl{};
        ring_ = SpscRing<Frame>(memory_, RingDescriptor{0, sizeof(Frame), capacity});
    }
    ~LocalRing() { ::operator delete (memory_, std::align_val_t{64}); }
    LocalRing(const LocalRing&) = delete;
    LocalRing& operator=(const LocalRing&) = delete;
    SpscRing<Frame>& ring() { return ring_; }
    const SpscRing<Frame>& ring() const { return ring_; }

  private:
    char* memory_;
    SpscRing<Frame> ring_;
};

}  // namespace archet::ipc
