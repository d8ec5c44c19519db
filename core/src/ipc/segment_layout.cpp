#include "archet/ipc/segment_layout.hpp"

#include <algorithm>
#include <array>

namespace archet::ipc {

namespace {

constexpr std::uint64_t kAlign = 64;
constexpr std::uint32_t kMaxCapacity = 1u << 20;

std::uint64_t align_up(std::uint64_t x) {
    return (x + kAlign - 1) / kAlign * kAlign;
}

std::uint64_t ring_bytes(const RingDescriptor& d) {
    return sizeof(RingControl) + static_cast<std::uint64_t>(d.capacity) * d.frame_size;
}

}  // namespace

Layout plan_layout(std::uint32_t command_capacity, std::uint32_t probe_capacity,
                   std::uint32_t shape_capacity, std::uint32_t status_capacity) {
    Layout h;
    h.magic = kMagic;
    h.protocol_version = kProtocolVersion;
    h.minimum_compatible_version = kMinimumCompatibleVersion;
    h.header_size = sizeof(SegmentHeader);
    std::uint64_t at = align_up(sizeof(SegmentHeader));
    auto place = [&](RingDescriptor& d, std::uint32_t frame_size, std::uint32_t capacity) {
        d = {at, frame_size, capacity};
        at = align_up(at + ring_bytes(d));
    };
    place(h.commands, sizeof(CommandFrame), command_capacity);
    place(h.probes, sizeof(ProbeFrame), probe_capacity);
    place(h.shapes, sizeof(ShapeFrame), shape_capacity);
    place(h.status, sizeof(StatusFrame), status_capacity);
    h.segment_size = at;
    return h;
}

Layout read_layout(const SegmentHeader& header) {
    Layout l;
    l.magic = header.magic;
    l.protocol_version = header.protocol_version;
    l.minimum_compatible_version = header.minimum_compatible_version;
    l.header_size = header.header_size;
    l.segment_size = header.segment_size;
    l.commands = header.commands, l.probes = header.probes, l.shapes = header.shapes,
    l.status = header.status;
    return l;
}

const char* validate_layout(const Layout& h, std::uint64_t mapped_size) {
    if (mapped_size < sizeof(SegmentHeader)) return "segment smaller than its header";
    if (h.magic != kMagic) return "not an Archet segment (bad magic)";
    if (h.protocol_version < kMinimumCompatibleVersion)
        return "segment protocol too old for this engine";
    if (h.minimum_compatible_version > kProtocolVersion) return "segment needs a newer engine";
    if (h.header_size != sizeof(SegmentHeader)) return "header size does not match this protocol";
    if (h.segment_size != mapped_size) return "segment size does not match the mapping";
    const std::array<std::pair<const RingDescriptor*, std::uint32_t>, 4> rings{{
        {&h.commands, sizeof(CommandFrame)},
        {&h.probes, sizeof(ProbeFrame)},
        {&h.shapes, sizeof(ShapeFrame)},
        {&h.status, sizeof(StatusFrame)},
    }};
    std::array<std::pair<std::uint64_t, std::uint64_t>, 4> spans{};
    for (std::size_t i = 0; i < rings.size(); ++i) {
        const RingDescriptor& d = *rings[i].first;
        if (d.frame_size != rings[i].second)
            return "a ring's frame size does not match this protocol";
        if (d.capacity < 2 || d.capacity > kMaxCapacity || (d.capacity & (d.capacity - 1)) != 0)
            return "a ring's capacity is not a power of two in range";
        if (d.offset % kAlign != 0) return "a ring is not aligned";
        if (d.offset < sizeof(SegmentHeader)) return "a ring overlaps the header";
        if (d.offset > mapped_size || ring_bytes(d) > mapped_size - d.offset)
            return "a ring runs past the segment";
        spans[i] = {d.offset, d.offset + ring_bytes(d)};
    }
    std::sort(spans.begin(), spans.end());
    for (std::size_t i = 1; i < spans.size(); ++i)
        if (spans[i].first < spans[i - 1].second) return "two rings overlap";
    return nullptr;
}

}  // namespace archet::ipc
