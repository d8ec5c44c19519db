#pragma once
// The one description of the memory the studio and the engine share. Plain data only, no
// pointers (each process maps it at its own address): a versioned header with the offsets of
// the rings that follow it. The studio creates and sizes the segment; the engine checks every
// field before trusting any of it (validate_layout).

#include <atomic>
#include <cstddef>
#include <cstdint>

namespace archet::ipc {

inline constexpr std::uint32_t kMagic = 0x54454843;  // "CHET" little-endian
/// 2: takes (StartTake, StopTake); 3: the running sample rate in the header and status frames,
/// the load as a share of the budget; 4: the block size in the header, which is then the one
/// place both read the rate from (status frames no longer carry it); 5: a shape frame says how
/// many string points its positions are spread over (a field that was reserved: a studio of
/// version 4 draws them as consecutive points, one of 5 takes an engine's 0 as "each point").
inline constexpr std::uint16_t kProtocolVersion = 5;
inline constexpr std::uint16_t kMinimumCompatibleVersion = 4;

inline constexpr std::size_t kMaxProbes = 16;  ///< probe values per probe frame
/// Samples between two readings of the stored energy in the probe frames, held in between: a
/// sum over the whole model, it costs nearly as much as a step (a take records every sample).
inline constexpr std::uint64_t kEnergyProbeEvery = 16;
inline constexpr std::size_t kMaxShapePoints = 512;  ///< string positions per shape frame
inline constexpr std::size_t kTextSize = 256;        ///< paths, ids and messages, NUL-terminated

/// Where a ring lives in the segment and what it carries.
struct RingDescriptor {
    std::uint64_t offset;      ///< from the segment start, to its RingControl
    std::uint32_t frame_size;  ///< bytes per frame
    std::uint32_t capacity;    ///< frames, a power of two
};

/// Indices of one single-producer/single-consumer ring, each on its own cache line.
/// Monotonic 64-bit counts: `written − read` frames are waiting.
struct RingControl {
    alignas(64) std::atomic<std::uint64_t> written;
    alignas(64) std::atomic<std::uint64_t> read;
    alignas(64) std::atomic<std::uint64_t> dropped;  ///< frames the producer gave up on: ring full
};

enum class EngineState : std::uint32_t {
    Starting = 0,
    Ready = 1,
    Running = 2,
    Exiting = 3,
    Failed = 4,
    Silent = 5  ///< the studio's heartbeat stopped: faded out, nothing plays until it beats
};

struct SegmentHeader {
    std::uint32_t magic;
    std::uint16_t protocol_version;
    std::uint16_t minimum_compatible_version;
    std::uint32_t header_size;
    std::uint32_t reserved;
    std::uint64_t segment_size;
    std::int32_t studio_pid;  ///< the owner, who created the segment
    std::atomic<std::int32_t> engine_pid;
    alignas(64) std::atomic<std::uint64_t> studio_heartbeat;  ///< counts up while the studio lives
    alignas(64) std::atomic<std::uint64_t> engine_heartbeat;  ///< counts up while the engine lives
    std::atomic<std::uint32_t> engine_state;                  ///< an EngineState
    // What the engine's device actually runs at, whatever the studio asked for: written by the
    // engine once its output is open (0 before), and read from here by the studio, nowhere else.
    /// Frames per audio block (per real-time callback).
    std::atomic<std::uint32_t> block_frames;
    /// Hz: the rate the engine runs the model at. Every time constant of the studio (scopes,
    /// spectra, fades) derives from it.
    std::atomic<double> sample_rate;
    RingDescriptor commands;  ///< studio → engine: CommandFrame
    RingDescriptor probes;    ///< engine → studio: ProbeFrame, one per audio sample
    RingDescriptor shapes;    ///< engine → studio: ShapeFrame, the string's positions
    RingDescriptor status;    ///< engine → studio: StatusFrame
};

// ---- Frames --------------------------------------------------------------------------------

/// Commands, studio → engine. Each names its payload; the engine validates every field.
enum class Opcode : std::uint32_t {
    LoadModel = 1,     ///< text: a model file path; compiled off the real-time thread, swapped in
    SetParameter = 2,  ///< text: "ELEMENT.PARAM", value
    Play = 3,          ///< start the simulation clock
    Stop = 4,          ///< stop it (silence, forces to zero)
    Gesture = 5,       ///< slide, press: the pad's device position (m)
    Quit = 6,          ///< leave cleanly
    StartTake = 7,     ///< text: a new (or empty) folder to record a take into
    StopTake = 8,      ///< finish the take being recorded
};

/// The opcode's name for logs and messages ("unknown" for none of them).
constexpr const char* opcode_name(Opcode op) {
    switch (op) {
        case Opcode::LoadModel:
            return "LoadModel";
        case Opcode::SetParameter:
            return "SetParameter";
        case Opcode::Play:
            return "Play";
        case Opcode::Stop:
            return "Stop";
        case Opcode::Gesture:
            return "Gesture";
        case Opcode::Quit:
            return "Quit";
        case Opcode::StartTake:
            return "StartTake";
        case Opcode::StopTake:
            return "StopTake";
    }
    return "unknown";
}
/// A frame's raw opcode field, which may be anything.
constexpr const char* opcode_name(std::uint32_t raw) {
    return opcode_name(static_cast<Opcode>(raw));
}

struct CommandFrame {
    std::uint32_t opcode;    ///< an Opcode
    std::uint32_t sequence;  ///< echoed in status frames that answer it
    double value;
    double slide, press;
    char text[kTextSize];
};

struct ProbeFrame {
    std::uint64_t tick;   ///< master clock tick of the sample
    std::uint32_t count;  ///< probe values used
    std::uint32_t reserved;
    double values[kMaxProbes];
    double output;  ///< the audio played (the model's output; cross-faded while models swap)
};

struct ShapeFrame {
    std::uint64_t tick;
    std::uint32_t count;  ///< positions used (the string's MATs, in model order)
    /// The string's points those are spread evenly over, from the bridge to the nut
    /// (drawn_points()): `count` when each is drawn, more for a string longer than
    /// kMaxShapePoints (0 from an engine before it said so: then as `count`).
    std::uint32_t spread_over;
    float positions[kMaxShapePoints];
};

enum class StatusKind : std::uint32_t {
    Heartbeat = 1,
    ModelLoaded = 2,
    Error = 3,
    Blowup = 4,
    Take = 5,  ///< text: "recording DIR" when a take begins, "written DIR ..." when it is done
    Midi = 6,  ///< a controller moved: sequence = its number (128: channel pressure), text says
};

/// The status kind's name for logs and messages ("unknown" for none of them).
constexpr const char* status_kind_name(StatusKind kind) {
    switch (kind) {
        case StatusKind::Heartbeat:
            return "Heartbeat";
        case StatusKind::ModelLoaded:
            return "ModelLoaded";
        case StatusKind::Error:
            return "Error";
        case StatusKind::Blowup:
            return "Blowup";
        case StatusKind::Take:
            return "Take";
        case StatusKind::Midi:
            return "Midi";
    }
    return "unknown";
}
constexpr const char* status_kind_name(std::uint32_t raw) {
    return status_kind_name(static_cast<StatusKind>(raw));
}

struct StatusFrame {
    std::uint32_t kind;      ///< a StatusKind
    std::uint32_t sequence;  ///< of the command answered, 0 otherwise
    std::uint64_t tick;
    std::uint64_t blocks;   ///< audio blocks processed
    std::uint64_t xruns;    ///< blocks that missed their deadline
    std::uint64_t dropped;  ///< probe frames dropped because the studio read too slowly
    double load;            ///< share of the real-time budget used over the last 0.2 s
    double worst_load;      ///< the longest block so far, as a fraction of one block's period
    double energy;          ///< J stored in the model
    std::uint64_t realtime_allocations;  ///< made on the real-time thread: must stay 0
    char text[kTextSize];                ///< model name, or what went wrong
};

static_assert(std::atomic<std::uint64_t>::is_always_lock_free,
              "rings need lock-free 64-bit atomics");
static_assert(std::atomic<std::uint32_t>::is_always_lock_free);
static_assert(std::atomic<double>::is_always_lock_free);

// The layout both processes map, pinned field by field (as JACK2 and SuperCollider do): a change
// fails to compile here, and must come with a new kProtocolVersion.
static_assert(offsetof(RingDescriptor, offset) == 0);
static_assert(offsetof(RingDescriptor, frame_size) == 8);
static_assert(offsetof(RingDescriptor, capacity) == 12);
static_assert(sizeof(RingDescriptor) == 16);

static_assert(offsetof(RingControl, written) == 0);
static_assert(offsetof(RingControl, read) == 64);
static_assert(offsetof(RingControl, dropped) == 128);
static_assert(sizeof(RingControl) == 192);

static_assert(offsetof(SegmentHeader, magic) == 0);
static_assert(offsetof(SegmentHeader, protocol_version) == 4);
static_assert(offsetof(SegmentHeader, minimum_compatible_version) == 6);
static_assert(offsetof(SegmentHeader, header_size) == 8);
static_assert(offsetof(SegmentHeader, reserved) == 12);
static_assert(offsetof(SegmentHeader, segment_size) == 16);
static_assert(offsetof(SegmentHeader, studio_pid) == 24);
static_assert(offsetof(SegmentHeader, engine_pid) == 28);
static_assert(offsetof(SegmentHeader, studio_heartbeat) == 64);
static_assert(offsetof(SegmentHeader, engine_heartbeat) == 128);
static_assert(offsetof(SegmentHeader, engine_state) == 136);
static_assert(offsetof(SegmentHeader, block_frames) == 140);
static_assert(offsetof(SegmentHeader, sample_rate) == 144);
static_assert(offsetof(SegmentHeader, commands) == 152);
static_assert(offsetof(SegmentHeader, probes) == 168);
static_assert(offsetof(SegmentHeader, shapes) == 184);
static_assert(offsetof(SegmentHeader, status) == 200);
static_assert(alignof(SegmentHeader) == 64);
static_assert(sizeof(SegmentHeader) == 256);

static_assert(offsetof(CommandFrame, opcode) == 0);
static_assert(offsetof(CommandFrame, sequence) == 4);
static_assert(offsetof(CommandFrame, value) == 8);
static_assert(offsetof(CommandFrame, slide) == 16);
static_assert(offsetof(CommandFrame, press) == 24);
static_assert(offsetof(CommandFrame, text) == 32);
static_assert(sizeof(CommandFrame) == 288);

static_assert(offsetof(ProbeFrame, tick) == 0);
static_assert(offsetof(ProbeFrame, count) == 8);
static_assert(offsetof(ProbeFrame, reserved) == 12);
static_assert(offsetof(ProbeFrame, values) == 16);
static_assert(offsetof(ProbeFrame, output) == 144);
static_assert(sizeof(ProbeFrame) == 152);

static_assert(offsetof(ShapeFrame, tick) == 0);
static_assert(offsetof(ShapeFrame, count) == 8);
static_assert(offsetof(ShapeFrame, spread_over) == 12);
static_assert(offsetof(ShapeFrame, positions) == 16);
static_assert(sizeof(ShapeFrame) == 2064);

static_assert(offsetof(StatusFrame, kind) == 0);
static_assert(offsetof(StatusFrame, sequence) == 4);
static_assert(offsetof(StatusFrame, tick) == 8);
static_assert(offsetof(StatusFrame, blocks) == 16);
static_assert(offsetof(StatusFrame, xruns) == 24);
static_assert(offsetof(StatusFrame, dropped) == 32);
static_assert(offsetof(StatusFrame, load) == 40);
static_assert(offsetof(StatusFrame, worst_load) == 48);
static_assert(offsetof(StatusFrame, energy) == 56);
static_assert(offsetof(StatusFrame, realtime_allocations) == 64);
static_assert(offsetof(StatusFrame, text) == 72);
static_assert(sizeof(StatusFrame) == 328);

/// The plain (non-atomic) fields of a header: what a layout is planned as, and what a reader
/// copies out of a segment before judging it.
struct Layout {
    std::uint32_t magic = 0;
    std::uint16_t protocol_version = 0;
    std::uint16_t minimum_compatible_version = 0;
    std::uint32_t header_size = 0;
    std::uint64_t segment_size = 0;
    RingDescriptor commands{}, probes{}, shapes{}, status{};
};

/// Sizes and offsets for a new segment with the given ring capacities.
Layout plan_layout(std::uint32_t command_capacity, std::uint32_t probe_capacity,
                   std::uint32_t shape_capacity, std::uint32_t status_capacity);

/// Copies the plain fields out of a (possibly hostile) mapped header.
Layout read_layout(const SegmentHeader& header);

/// What a reader found wrong with a layout, or nullptr when it is sound.
const char* validate_layout(const Layout& layout, std::uint64_t mapped_size);

}  // namespace archet::ipc
