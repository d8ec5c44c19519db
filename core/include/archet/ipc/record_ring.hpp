#pragma once
// A single-producer/single-consumer ring in this process's memory whose records are each the
// same number of doubles, chosen when it is made: a take's samples, each as long as the model
// has probes (an SpscRing's frames have a size fixed when compiled). The producer claims the
// next record, fills it and publishes it; the consumer reads the oldest and releases it. Neither
// allocates, locks or waits: the memory is taken, and touched, when the ring is made.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "archet/ipc/segment_layout.hpp"

namespace archet::ipc {

class RecordRing {
  public:
    /// Room for `capacity` records (a power of two) of `length` doubles each.
    RecordRing(std::size_t length, std::uint32_t capacity)
        : length_(length),
          mask_(capacity - 1),
          records_(std::make_unique<double[]>(checked_doubles(length, capacity))) {}
    RecordRing(const RecordRing&) = delete;
    RecordRing& operator=(const RecordRing&) = delete;

    std::size_t length() const { return length_; }
    std::uint32_t capacity() const { return mask_ + 1; }

    // ---- producer ----
    /// The next record to fill, or null when the ring is full (the record is then counted as
    /// dropped). publish() hands it over: only after a claim that gave a record.
    double* claim() {
        const std::uint64_t w = control_.written.load(std::memory_order_relaxed);
        const std::uint64_t r = control_.read.load(std::memory_order_acquire);
        if (w - r > mask_) {
            control_.dropped.fetch_add(1, std::memory_order_relaxed);
            return nullptr;
        }
        return record(w);
    }
    void publish() {
        const std::uint64_t w = control_.written.load(std::memory_order_relaxed);
        control_.written.store(w + 1, std::memory_order_release);
    }

    // ---- consumer ----
    /// The oldest record published, or null when none waits. release() frees its room.
    const double* front() {
        const std::uint64_t r = control_.read.load(std::memory_order_relaxed);
        const std::uint64_t w = control_.written.load(std::memory_order_acquire);
        return w == r ? nullptr : record(r);
    }
    void release() {
        const std::uint64_t r = control_.read.load(std::memory_order_relaxed);
        control_.read.store(r + 1, std::memory_order_release);
    }

    /// Records the producer could not claim because the ring was full.
    std::uint64_t dropped() const { return control_.dropped.load(std::memory_order_relaxed); }

  private:
    static std::size_t checked_doubles(std::size_t length, std::uint32_t capacity) {
        if (length == 0 || capacity == 0 || (capacity & (capacity - 1)) != 0 ||
            length > SIZE_MAX / sizeof(double) / capacity)
            throw std::invalid_argument(
                "a record ring holds a power of two of non-empty records that fit in memory");
        return length * capacity;
    }
    double* record(std::uint64_t index) const { return records_.get() + (index & mask_) * length_; }

    std::size_t length_;
    std::uint32_t mask_;
    std::unique_ptr<double[]> records_;  ///< zeroed: its pages are mapped before any claim
    RingControl control_{};
};

}  // namespace archet::ipc
