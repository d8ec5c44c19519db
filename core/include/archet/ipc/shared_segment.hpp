#pragma once
// The POSIX shared-memory segment between the studio and the engine. The studio creates it
// exclusively (O_CREAT|O_EXCL), mode 0600, under an unguessable name, and unlinks it when done;
// the engine attaches and checks the owner, the permissions and every field of the layout.

#include <string>
#include <vector>

#include "archet/ipc/segment_layout.hpp"
#include "archet/ipc/spsc_ring.hpp"

namespace archet::ipc {

class SharedSegment {
  public:
    /// Creates a new segment laid out as `plan`; the calling process is its owner.
    static SharedSegment create(const Layout& plan);
    /// Maps an existing segment and validates it; throws InputError saying what is wrong.
    static SharedSegment attach(const std::string& name);

    SharedSegment(SharedSegment&& other) noexcept;
    SharedSegment& operator=(SharedSegment&& other) noexcept;
    SharedSegment(const SharedSegment&) = delete;
    SharedSegment& operator=(const SharedSegment&) = delete;
    ~SharedSegment();

    const std::string& name() const { return name_; }
    SegmentHeader& header() { return *static_cast<SegmentHeader*>(base_); }
    void* base() { return base_; }
    std::uint64_t size() const { return size_; }

    // Rings from the layout as validated (or planned): later writes to the header by the
    // other side cannot move them.
    SpscRing<CommandFrame> commands() { return {base_, layout_.commands}; }
    SpscRing<ProbeFrame> probes() { return {base_, layout_.probes}; }
    SpscRing<ShapeFrame> shapes() { return {base_, layout_.shapes}; }
    SpscRing<StatusFrame> status() { return {base_, layout_.status}; }

    /// Removes the name (the mapping stays valid until unmapped). The owner does it on
    /// destruction; an engine whose studio died does it for it.
    void unlink();

  private:
    SharedSegment() = default;
    std::string name_;
    void* base_ = nullptr;
    std::uint64_t size_ = 0;
    bool owner_ = false;
    Layout layout_;
};

/// "/archet-" and 32 random hex digits.
std::string random_segment_name();

/// Removes the segments left behind when a studio and its engine both died (neither could
/// unlink it). Only this user's own: names "archet-" and 32 hex digits in `folder` (where
/// shm_open keeps them), mode 0600, owned by this user, with a valid header of this protocol,
/// whose studio and engine pids are both gone. Returns the names removed ("/archet-...").
std::vector<std::string> reclaim_stale_segments(const std::string& folder = "/dev/shm");

/// Whether process `pid` is gone (no such process; a zombie or another user's still counts).
bool process_gone(std::int32_t pid);

}  // namespace archet::ipc
