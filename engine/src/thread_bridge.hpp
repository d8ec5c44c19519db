#pragma once
// All that the engine's control thread and its real-time thread share: lock-free rings local
// to the process, and atomics that one thread publishes and the other takes (a model offered
// or handed back is exchanged for null by the side that takes it; a flag is set by one side
// and cleared by the other). Once the device has stopped, the control thread has both ends.
// Nothing here blocks.

#include <atomic>
#include <cstdint>

#include "archet/ipc/spsc_ring.hpp"
#include "archet/physics/compiled_model.hpp"
#include "loaded_model.hpp"

namespace archet {

class TakeRecorder;

/// Work the control thread hands to the real-time thread.
struct RealtimeCommand {
    enum Kind : std::uint32_t {
        SetParameter,
        Gesture,
        BowDrive,  ///< the bow slides on by itself at `value` m/s (signed), pressed at `press`
        Play,
        Stop,
        StartTake,
        StopTake
    } kind;
    ParameterSlot slot;
    double value, slide, press;
    TakeRecorder* take = nullptr;  ///< StartTake: the recorder, owned by the real-time thread
    std::uint64_t generation = 0;  ///< StartTake, SetParameter: the model load it was made for
    std::uint32_t name = 0;        ///< SetParameter: its name in the take being recorded
    bool named = false;            ///< SetParameter: `name` is set (a take was started)
};

struct ThreadBridge {
    ThreadBridge() : to_realtime(1024), finished_takes(16) {}
    ~ThreadBridge() {  // both threads have stopped
        delete pending.load();
        delete retired.load();
    }
    ThreadBridge(const ThreadBridge&) = delete;
    ThreadBridge& operator=(const ThreadBridge&) = delete;

    // ---- control → real-time ----
    ipc::LocalRing<RealtimeCommand> to_realtime;
    /// A compiled model waiting for a block boundary: stored by control, taken by real-time.
    std::atomic<LoadedModel*> pending{nullptr};
    std::atomic<bool> silent{false};  ///< the studio froze: fade out, play nothing

    // ---- real-time → control ----
    ipc::LocalRing<TakeRecorder*> finished_takes;    ///< takes to finish (ended, replaced, unused)
    std::atomic<LoadedModel*> retired{nullptr};      ///< a model let go of, to delete
    std::atomic<std::uint32_t> swapped_sequence{0};  ///< the load command of the last swap
    std::atomic<std::uint64_t> swaps{0};             ///< models swapped in so far
    std::atomic<bool> blown{false};  ///< the model blew up and is muted: control resets it
    std::atomic<std::uint64_t> tick{0}, blocks{0};  ///< for status frames
    std::atomic<double> energy{0};
    std::atomic<double> bow_force{0}, friction{0};  ///< the first bow's, at the last block
};

}  // namespace archet
