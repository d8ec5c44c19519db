#include "control_thread.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>
#include <variant>

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/engine/take_recorder.hpp"
#include "archet/files/model_file.hpp"
#include "archet/interruption.hpp"
#include "archet/ipc/command_decoder.hpp"
#include "archet/ipc/take_folder.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/simulation.hpp"
#include "loaded_model.hpp"

namespace archet {

using namespace ipc;

ControlThread::ControlThread(SharedSegment segment, const EngineOptions& options,
                             std::int32_t studio_pid)
    : segment_(std::move(segment)),
      options_(options),
      studio_pid_(studio_pid),
      commands_(segment_.commands()),
      publisher_(bridge_, segment_.status(), segment_.probes()) {}

ControlThread::~ControlThread() {
    if (output_) output_->stop();
}

int ControlThread::nrt_run() {
    const std::string said = nrt_open();
    segment_.header().engine_state.store(static_cast<std::uint32_t>(EngineState::Ready));
    publisher_.nrt_publish(StatusKind::Heartbeat, 0, said);
    nrt_loop();
    return nrt_shut_down();
}

// Opens the device and starts the real-time thread; returns what the studio is told of it.
std::string ControlThread::nrt_open() {
    auto& header = segment_.header();
    header.engine_pid.store(static_cast<std::int32_t>(::getpid()));
    watch_.emplace(studio_pid_, options_.studio_timeout, options_.studio_give_up, header,
                   bridge_.silent, publisher_);
    std::string said = nrt_request_realtime_resources();
    if (!options_.takes.empty()) {
        try {
            take_root_ = prepare_take_directory(options_.takes);
        } catch (const std::exception& e) {
            take_problem_ = e.what();
            said += take_problem_ + "; ";
        }
    }
    if (options_.osc_port > 0) {  // a port taken costs OSC, not the engine: it says so
        try {
            osc_ = std::make_unique<OscReceiver>(options_.osc_host, options_.osc_port);
            said += "OSC on " + options_.osc_host + ":" + std::to_string(options_.osc_port) + "; ";
        } catch (const std::exception& e) {
            said += std::string("no OSC: ") + e.what() + "; ";
        }
    }
    if (!options_.midi.empty()) {  // as for OSC: a port that cannot be had costs MIDI alone
        try {
            midi_ =
                std::make_unique<MidiReceiver>(MidiInputOptions{options_.midi_api, options_.midi});
            said += "MIDI from " + midi_->description() + "; ";
        } catch (const std::exception& e) {
            said += std::string("no MIDI: ") + e.what() + "; ";
        }
    }
    if (!options_.osc_send.empty()) {
        try {
            osc_out_ = std::make_unique<OscSender>(options_.osc_send);
            said += "OSC out to " + options_.osc_send + "; ";
        } catch (const std::exception& e) {
            said += std::string("no OSC out: ") + e.what() + "; ";
        }
    }
    haptic_ = open_haptic_device(options_.haptic);
    std::string warning;
    output_ = open_audio_output(options_.audio, &warning);
    sample_rate_ = output_->sample_rate();
    // What the studio derives its clocks from: the device's, whatever it was asked for.
    header.sample_rate.store(sample_rate_);
    header.block_frames.store(static_cast<std::uint32_t>(output_->buffer_frames()));
    publisher_.nrt_set_output(output_.get());
    rt_ = std::make_unique<RealtimeThread>(
        bridge_, segment_.probes(), segment_.shapes(),
        RealtimeThread::Setup{sample_rate_, options_.shape_every, haptic_.device != nullptr});
    said += output_->description() + ", " + std::to_string(output_->buffer_frames()) + " frames";
    if (!warning.empty()) said = warning + "; " + said;
    if (!haptic_.note.empty()) said += "; " + haptic_.note;
    output_->start(*rt_);
    said += "; " + output_->scheduling();
    return said;
}

std::string ControlThread::nrt_request_realtime_resources() const {
    if (!options_.lock_memory) return "memory not locked (not asked to); ";
    if (::mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
        return "memory not locked (" + std::string(std::strerror(errno)) + "); ";
    return "memory locked; ";
}

void ControlThread::nrt_loop() {
    auto& header = segment_.header();
    auto last_status = std::chrono::steady_clock::now();
    watch_->nrt_begin();
    while (!quit_) {
        header.engine_heartbeat.fetch_add(1);
        // SIGINT, SIGTERM, SIGHUP (InterruptionGuard) end the loop and the takes finish.
        const StudioWatch::Verdict verdict = watch_->nrt_check(interruption_signal());
        if (verdict == StudioWatch::Verdict::StudioExited) {
            // Nobody will read or unlink the segment: silence, clean up, leave.
            segment_.unlink();
            take_interruption_ = "the studio exited";
            break;
        }
        if (verdict != StudioWatch::Verdict::Stay) break;
        CommandFrame command;
        while (commands_.try_pop(command)) nrt_handle(command);
        if (moving_bow_) nrt_send_waiting_changes();
        if (bow_wanted_ > 0) nrt_move_bow(bow_wanted_, bow_wanted_by_);
        if (osc_) nrt_take_osc();
        if (midi_) nrt_take_midi();
        nrt_collect_retired();
        nrt_collect_takes();
        if (bridge_.blown.exchange(false)) nrt_recover_from_blowup();
        if (std::chrono::steady_clock::now() - last_status > std::chrono::milliseconds(50)) {
            publisher_.nrt_publish(StatusKind::Heartbeat, 0, current_name_);
            if (midi_) nrt_show_controllers();
            if (osc_out_)
                osc_out_->send(bridge_.bow_force.load(), bridge_.friction.load(),
                               bridge_.energy.load());
            last_status = std::chrono::steady_clock::now();
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
}

int ControlThread::nrt_shut_down() {
    segment_.header().engine_state.store(static_cast<std::uint32_t>(EngineState::Exiting));
    output_->stop();
    nrt_collect_retired();
    // The real-time thread has stopped: its takes are the control thread's to finish.
    rt_->nrt_hand_back_takes();
    const bool studio_exited = !take_interruption_.empty();
    const int signal = studio_exited ? 0 : interruption_signal();
    if (signal) take_interruption_ = signal_name(signal);
    nrt_collect_takes();
    delete bridge_.pending.exchange(nullptr);
    rt_->nrt_release_models();
    return signal ? 128 + signal : 0;
}

void ControlThread::nrt_fail(const CommandFrame& c, const std::string& message) {
    publisher_.nrt_publish(StatusKind::Error, c.sequence, message);
}

void ControlThread::nrt_handle(const CommandFrame& c) {
    const auto decoded = decode_command(c);  // every field checked: it came from outside
    if (const auto* why = std::get_if<std::string>(&decoded)) return nrt_fail(c, *why);
    const DecodedCommand& d = std::get<DecodedCommand>(decoded);
    switch (d.opcode) {
        case Opcode::LoadModel:
            return nrt_load(c, d.text);
        case Opcode::SetParameter:
            return nrt_set_live_parameter(c, d.parameter);
        case Opcode::Play:
            return nrt_send({RealtimeCommand::Play, {}, 0, 0, 0}, c);
        case Opcode::Stop:
            return nrt_send({RealtimeCommand::Stop, {}, 0, 0, 0}, c);
        case Opcode::Gesture:
            osc_hand_ = {d.slide, d.press};  // OSC moves one axis from where the pad left both
            return nrt_send({RealtimeCommand::Gesture, {}, 0, d.slide, d.press}, c);
        case Opcode::Quit:
            quit_ = true;
            return;
        case Opcode::StartTake:
            return nrt_start_take(c, d.text);
        case Opcode::StopTake:
            return nrt_send({RealtimeCommand::StopTake, {}, 0, 0, 0}, c);
    }
}

void ControlThread::nrt_send(const RealtimeCommand& r, const CommandFrame& c) {
    if (!bridge_.to_realtime.ring().try_push(r))
        nrt_fail(c, std::string("the real-time thread is behind; ") + opcode_name(c.opcode) +
                        " dropped");
}

void ControlThread::nrt_load(const CommandFrame& c, const std::string& path) {
    try {
        Model model = load_model_file(path);
        model.sample_rate = sample_rate_;  // it runs at the device's rate: checked at it
        validate_model(model);
        if (model.probes.size() > kMaxProbes)
            throw InputError(path, "has " + std::to_string(model.probes.size()) +
                                       " probes; the engine streams at most " +
                                       std::to_string(kMaxProbes));
        auto loaded = nrt_prepare_model(model, sample_rate_, haptic_, c.sequence, generation_);
        nrt_check_cost(path, *loaded, sample_rate_, output_->buffer_frames());
        loaded->generation = ++generation_;  // only once it compiled
        current_resolver_ = loaded->resolver;
        current_build_ = loaded->simulation->chain_build();
        current_model_ = std::move(model);
        current_name_ = current_model_.name;
        glided_slots_.clear();  // the new model's slots are its own
        if (midi_) nrt_prepare_performer();
        delete bridge_.pending.exchange(loaded.release());  // an unclaimed older one is dropped
    } catch (const std::exception& e) {
        nrt_fail(c, e.what());
    }
}

void ControlThread::nrt_set_live_parameter(const CommandFrame& c, const ParameterName& name) {
    // Not a value that glides: the string goes on in a model with its bow moved.
    if (name.text() == "bow.position") return nrt_move_bow(c.value, c);
    // The moved model takes over the playing one's state, parameters included: a change made
    // in between would be lost, so it waits the millisecond or two until the hand-over.
    if (moving_bow_ && bridge_.pending.load()) {
        waiting_changes_.push_back({c, name});
        return;
    }
    try {
        if (current_name_.empty()) throw InputError(name.text(), "no model is loaded");
        const ParameterSlot slot = current_resolver_.resolve_parameter(name);
        // The trust boundary: the studio checked the value, but commands come from another
        // process, and the engine runs at its device's rate. Range and stability, once.
        set_parameter_validated(current_model_, name, c.value);
        nrt_set_in_waiting_model(slot, c.value);
        nrt_remember_slot(slot, name.text());
        RealtimeCommand r{RealtimeCommand::SetParameter, slot, c.value, 0, 0};
        r.generation = generation_;  // the real-time thread applies it to that model only
        if (live_take_) r.name = live_take_->parameter_name(name.text()), r.named = true;
        nrt_send(r, c);
    } catch (const std::exception& e) {
        nrt_fail(c, e.what());
    }
}

// Each slot a parameter change glides, by name: a take that begins while one glides names it.
void ControlThread::nrt_remember_slot(const ParameterSlot& slot, const std::string& name) {
    for (const auto& [known, _] : glided_slots_)
        if (known == slot) return;
    glided_slots_.push_back({slot, name});
}

void ControlThread::nrt_send_waiting_changes() {
    if (bridge_.pending.load()) return;  // not yet taken over
    moving_bow_ = false;
    auto changes = std::move(waiting_changes_);
    waiting_changes_.clear();
    for (const auto& [c, name] : changes) nrt_set_live_parameter(c, name);
}

// A model loaded but not yet swapped in was compiled before this change: it gets the value
// here (the real-time thread leaves the command to the model it was resolved for).
void ControlThread::nrt_set_in_waiting_model(const ParameterSlot& slot, double value) {
    LoadedModel* waiting = bridge_.pending.exchange(nullptr, std::memory_order_acq_rel);
    if (!waiting) return;  // none, or the real-time thread took it: the command will do
    waiting->simulation->write_slot(slot, value);
    delete bridge_.pending.exchange(waiting, std::memory_order_acq_rel);  // only this stores
}

// Opens the take's files here, off the real-time path, and hands the recorder over; the
// real-time thread begins it at a block boundary.
void ControlThread::nrt_start_take(const CommandFrame& c, const std::string& folder) {
    try {
        // The folder came from another process: nothing is made until it is known to lie
        // inside the take directory the studio gave at start.
        if (!take_problem_.empty()) throw InputError(quoted_text(folder), take_problem_);
        // Recorded where the check resolved it, not where a link swapped in since points.
        const std::filesystem::path inside = check_take_folder(folder, take_root_);
        if (current_name_.empty()) throw InputError(folder, "no model is loaded to record");
        if (live_take_)
            throw InputError(folder, "a take is already being recorded into " +
                                         live_take_->folder().string() + "; stop it first");
        std::vector<std::string> probes;
        for (const auto& p : current_resolver_.probes) probes.push_back(p.id);
        const std::size_t state_size = Simulation(current_resolver_).state_size();
        auto take = std::make_unique<TakeRecorder>(inside, current_model_, sample_rate_, probes,
                                                   state_size);
        for (const auto& [slot, name] : glided_slots_) take->name_slot(slot, name);
        RealtimeCommand r{RealtimeCommand::StartTake, {}, 0, 0, 0};
        r.take = take.get();
        r.generation = generation_;
        if (!bridge_.to_realtime.ring().try_push(r))
            throw InputError(folder, "the real-time thread is behind; take not started");
        live_take_ = take.release();  // the real-time thread owns it until it hands it back
        publisher_.nrt_publish(StatusKind::Take, c.sequence, "recording " + folder);
    } catch (const std::exception& e) {
        nrt_fail(c, e.what());
    }
}

// Finishes the takes the real-time thread handed back (ended, replaced or never begun).
void ControlThread::nrt_collect_takes() {
    TakeRecorder* take = nullptr;
    while (bridge_.finished_takes.ring().try_pop(take)) {
        if (take == live_take_) live_take_ = nullptr;
        const std::string said = nrt_finish_take(*take);
        delete take;
        publisher_.nrt_publish(StatusKind::Take, 0, said);
    }
}

// Writes the take's last files; returns what the studio is told.
std::string ControlThread::nrt_finish_take(TakeRecorder& take) {
    std::string said = "written " + take.folder().string();
    // Why the engine ended it early, if it did: take.json says so.
    std::string why = take_interruption_;
    if (why.empty() && bridge_.blown.load())
        why = "the model blew up (energy runaway or non-finite output) and was reset";
    if (why.empty() && watch_->nrt_silenced()) why = "the studio stopped answering";
    try {
        take.finish(why);
        said += " (" + std::to_string(take.frames()) + " samples";
        if (!why.empty()) said += ", interrupted: " + why;
        said += ")";
        // Short: a status frame holds ipc::kTextSize characters, the folder's name among them.
        if (take.dropped_samples() > 0 || take.dropped_events() > 0)
            said += "; incomplete: lost " + std::to_string(take.dropped_samples()) + " samples, " +
                    std::to_string(take.dropped_events()) + " events";
        // The live limiter kept the monitor clean; the take holds the raw output.
        if (take.clipped_samples() > 0) {
            char peak[32];
            std::snprintf(peak, sizeof peak, "%.2f", take.peak());
            said += "; " + std::to_string(take.clipped_samples()) +
                    " samples clipped at full scale (peak " + peak +
                    "): " + gain_advice(take.peak());
        }
    } catch (const std::exception& e) {
        said = std::string("take failed: ") + e.what();
    }
    return said;
}

// Deletes what the real-time thread let go of, and answers each model swap it made.
void ControlThread::nrt_collect_retired() {
    delete bridge_.retired.exchange(nullptr, std::memory_order_acq_rel);
    const std::uint64_t swaps = bridge_.swaps.load(std::memory_order_acquire);
    if (swaps != swaps_answered_) {
        swaps_answered_ = swaps;
        publisher_.nrt_publish(StatusKind::ModelLoaded, bridge_.swapped_sequence.load(),
                               current_name_);
    }
}

// The real-time thread muted the model; a fresh copy of the current one replaces it.
void ControlThread::nrt_recover_from_blowup() {
    delete bridge_.pending.exchange(
        nrt_prepare_model(current_model_, sample_rate_, haptic_, 0, generation_, current_build_)
            .release());
    publisher_.nrt_publish(
        StatusKind::Blowup, 0,
        "energy runaway or non-finite output: muted within the block, model reset");
}

}  // namespace archet
