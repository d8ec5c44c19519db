#pragma once
// The engine's control thread (non-real-time): the process's main thread. It opens the device
// and starts the real-time thread, then every 2 ms validates and answers the studio's commands,
// loads and compiles models, resolves parameter names, watches the studio (StudioWatch),
// publishes status (StatusPublisher), finishes the takes and deletes the models the real-time
// thread hands back; at the end it stops the device and finishes what was left.
//
// Ownership: all members are the control thread's. It shares with the real-time thread only
// `bridge_`, and the objects passed through it (LoadedModel, TakeRecorder) while they are the
// real-time thread's.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "archet/audio_output.hpp"
#include "archet/engine/engine_options.hpp"
#include "archet/engine/midi_receiver.hpp"
#include "archet/engine/osc_receiver.hpp"
#include "archet/engine/osc_sender.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/ipc/shared_segment.hpp"
#include "archet/midi/midi_performer.hpp"
#include "archet/model/model.hpp"
#include "archet/model/parameter_name.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "realtime_thread.hpp"
#include "status_publisher.hpp"
#include "studio_watch.hpp"
#include "thread_bridge.hpp"

namespace archet {

class ControlThread {
  public:
    ControlThread(ipc::SharedSegment segment, const EngineOptions& options,
                  std::int32_t studio_pid);
    ~ControlThread();
    ControlThread(const ControlThread&) = delete;
    ControlThread& operator=(const ControlThread&) = delete;

    /// Until told to quit, a signal, or the studio's end; returns the exit status.
    int nrt_run();

  private:
    std::string nrt_open();
    std::string nrt_request_realtime_resources() const;
    void nrt_loop();
    int nrt_shut_down();

    void nrt_handle(const ipc::CommandFrame& c);
    void nrt_send(const RealtimeCommand& r, const ipc::CommandFrame& c);
    void nrt_fail(const ipc::CommandFrame& c, const std::string& message);
    void nrt_load(const ipc::CommandFrame& c, const std::string& path);
    void nrt_set_live_parameter(const ipc::CommandFrame& c, const ParameterName& name);
    void nrt_set_in_waiting_model(const ParameterSlot& slot, double value);
    void nrt_remember_slot(const ParameterSlot& slot, const std::string& name);
    void nrt_start_take(const ipc::CommandFrame& c, const std::string& folder);
    void nrt_collect_takes();
    std::string nrt_finish_take(TakeRecorder& take);
    void nrt_collect_retired();
    void nrt_recover_from_blowup();
    void nrt_take_osc();
    void nrt_handle_osc(const ipc::OscCommand& c);
    void nrt_prepare_performer();
    void nrt_take_midi();
    void nrt_note_controllers(const std::vector<midi::MidiMessage>& messages);
    void nrt_show_controllers();
    void nrt_move_bow(double beta, const std::optional<ipc::CommandFrame>& command);
    void nrt_send_waiting_changes();
    void nrt_say_midi(const std::string& what);

    ipc::SharedSegment segment_;
    const EngineOptions options_;
    const std::int32_t studio_pid_;  ///< fixed at start
    ipc::SpscRing<ipc::CommandFrame> commands_;
    HapticChoice haptic_;  ///< the device, used by the real-time thread (none by default)
    ThreadBridge bridge_;  ///< declared before what uses it, after the haptic device it holds
    StatusPublisher publisher_;
    std::optional<StudioWatch> watch_;
    std::unique_ptr<OscReceiver> osc_;    ///< with --osc
    std::unique_ptr<OscSender> osc_out_;  ///< with --osc-send
    GestureSample osc_hand_{};            ///< where OSC or the pad last put the device's axes
    bool osc_hand_moved_ = false;         ///< in the messages being handled
    std::uint64_t osc_takes_ = 0;         ///< takes started from OSC, for their names
    std::uint64_t osc_dropped_said_ = 0;  ///< dropped messages already reported
    std::unique_ptr<MidiReceiver> midi_;  ///< with --midi
    std::optional<midi::MidiPerformer> performer_;        ///< plays the loaded model from MIDI
    std::uint64_t midi_blocks_ = 0;                       ///< blocks played at the last MIDI round
    std::uint64_t midi_dropped_said_ = 0;                 ///< dropped messages already reported
    std::map<int, midi::MidiMessage> controllers_heard_;  ///< since the last status, newest
    /// A bow position asked for and not yet made (0: none), and the command that asked (none:
    /// MIDI), which hears what goes wrong.
    double bow_wanted_ = 0;
    std::optional<ipc::CommandFrame> bow_wanted_by_;
    std::vector<bool> unplayable_routes_;  ///< the map's parameters this model has not
    bool moving_bow_ = false;  ///< the moved model waits to take over: changes wait with it
    std::vector<std::pair<ipc::CommandFrame, ParameterName>> waiting_changes_;
    std::unique_ptr<RealtimeThread> rt_;   ///< built once the device is open
    std::unique_ptr<AudioOutput> output_;  ///< destroyed first: it calls rt_
    double sample_rate_ = 48000;           ///< the device's clock, the master: set once open
    bool quit_ = false;
    std::uint64_t swaps_answered_ = 0;
    std::filesystem::path take_root_;    ///< canonical take directory (empty: no takes)
    std::string take_problem_;           ///< why the take directory could not be used
    TakeRecorder* live_take_ = nullptr;  ///< the take it last started
    std::string take_interruption_;      ///< why takes end early, if they do
    // The view of the model the studio last loaded, for names and checks.
    Model current_model_;
    CompiledModel current_resolver_;
    /// Its bowed chain loop's build, timed when it was loaded: its bow moves keep it.
    std::optional<ChainBuild> current_build_;
    /// The slots parameter changes have glided in this model, with their names.
    std::vector<std::pair<ParameterSlot, std::string>> glided_slots_;
    std::string current_name_;
    std::uint64_t generation_ = 0;  ///< models loaded so far
};

}  // namespace archet
