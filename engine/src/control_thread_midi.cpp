// The engine's control thread playing from MIDI (midi_receiver.hpp): one member group of
// ControlThread, in a file of its own. The performer (core/midi) turns the messages into the
// hand's motion and parameter changes, which go the way the pad's and OSC's go: checked here,
// glided in on the real-time thread, recorded by a take.
#include <cstdio>

#include "archet/engine/take_recorder.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/model/string_points.hpp"
#include "control_thread.hpp"

namespace archet {

using namespace ipc;

// A performer for the model just loaded; a model MIDI cannot bow is
// said once and then not played from MIDI.
void ControlThread::nrt_prepare_performer() {
    // A note held over a new model: the new performer holds none, so the bow it drove lifts.
    if (performer_ && performer_->bowing()) {
        CommandFrame lift{};
        lift.opcode = static_cast<std::uint32_t>(Opcode::Gesture);
        nrt_send({RealtimeCommand::BowDrive, {}, 0, 0, 0}, lift);
        osc_hand_.press = 0;
    }
    performer_.reset();
    try {
        performer_.emplace(options_.midi_mapping, midi::performed_model(current_model_));
    } catch (const std::exception& e) {
        nrt_say_midi(std::string("this model is not played from MIDI: ") + e.what());
    }
    // A map's parameter this model has not is said once, not at every move of its controller.
    const auto& routes = options_.midi_mapping.controls;
    unplayable_routes_.assign(routes.size(), false);
    for (std::size_t i = 0; i < routes.size(); ++i) {
        if (routes[i].target != midi::MidiTarget::Parameter) continue;
        try {
            current_resolver_.resolve_parameter(routes[i].parameter);
        } catch (const std::exception& e) {
            unplayable_routes_[i] = true;
            nrt_say_midi("controller " + std::to_string(routes[i].controller) +
                         " does nothing with this model: " + e.what());
        }
    }
}

void ControlThread::nrt_say_midi(const std::string& what) {
    std::fprintf(stderr, "archet engine: MIDI: %s\n", what.c_str());
    nrt_fail({}, "MIDI: " + what);
}

// The bow's contact moved along the string (STK's CC 4, or the parameter `bow.position` from the
// studio or OSC): the playing model with its bow module on the mass nearest β, compiled here,
// takes over the string's motion on the real-time thread (no restart). Nothing happens until β
// reaches another mass. A take recording keeps the move. `command`: the command that asked,
// which hears what goes wrong (none: MIDI, whose problems are said as such).
void ControlThread::nrt_move_bow(double beta, const std::optional<CommandFrame>& command) {
    bow_wanted_ = beta;  // kept until it is done: the last of a sweep must not be lost
    bow_wanted_by_ = command;
    try {
        if (current_name_.empty() || bridge_.pending.load()) return;  // one move at a time
        bow_wanted_ = 0;
        Model moved = current_model_;
        set_variant_parameter(moved, "bow.position", beta);
        const Lia* bow = first_bow(moved);
        const Lia* was = first_bow(current_model_);
        if (!bow || !was || bowed_centre(moved, *bow) == bowed_centre(current_model_, *was)) return;
        validate_model(moved);
        auto loaded =
            nrt_prepare_model(moved, sample_rate_, haptic_, 0, generation_, current_build_);
        loaded->continues = true;
        loaded->handover.resize(loaded->simulation->state_size());
        loaded->generation = ++generation_;
        if (live_take_) {  // the take goes on, and keeps the move
            loaded->bow_move_named = true;
            loaded->bow_move_name = live_take_->parameter_name("bow.position");
            loaded->bow_position = beta;
        }
        moving_bow_ =
            true;  // parameter changes wait for the hand-over (see nrt_set_live_parameter)
        current_resolver_ = loaded->resolver;
        current_model_ = std::move(moved);
        delete bridge_.pending.exchange(loaded.release());
    } catch (const std::exception& e) {
        const std::string why = std::string("bow position: ") + e.what();
        if (command)
            nrt_fail(*command, why);
        else
            nrt_say_midi(why);
    }
}

// The studio hears which controllers moved, for MIDI learn: the newest value of each, with the
// status every 50 ms (a swept controller must not crowd errors out of the status ring).
void ControlThread::nrt_note_controllers(const std::vector<midi::MidiMessage>& messages) {
    for (const auto& m : messages) {
        if (m.kind == midi::MidiMessage::Kind::Control)
            controllers_heard_[m.number] = m;
        else if (m.kind == midi::MidiMessage::Kind::ChannelPressure)
            controllers_heard_[midi::kChannelPressure] = m;
    }
}

void ControlThread::nrt_show_controllers() {
    for (const auto& [controller, m] : controllers_heard_)
        publisher_.nrt_publish(StatusKind::Midi, static_cast<std::uint32_t>(controller),
                               midi::describe(m));
    controllers_heard_.clear();
}

// The messages since the last round, then the performer's vibrato moved on by the sound played
// since (the audio clock, so it keeps pace with the sound even when this thread is late).
void ControlThread::nrt_take_midi() {
    const std::vector<midi::MidiMessage> messages = midi_->take();
    if (const std::string problem = midi_->take_problem(); !problem.empty()) nrt_say_midi(problem);
    if (const std::uint64_t dropped = midi_->dropped(); dropped > midi_dropped_said_) {
        midi_dropped_said_ = dropped;
        nrt_say_midi(std::to_string(dropped) + " messages dropped so far: they came faster " +
                     "than the engine reads them");
    }
    const std::uint64_t blocks = bridge_.blocks.load(std::memory_order_relaxed);
    const double seconds =
        static_cast<double>(blocks - midi_blocks_) * output_->buffer_frames() / sample_rate_;
    midi_blocks_ = blocks;
    nrt_note_controllers(messages);
    if (!performer_) return;
    for (const auto& m : messages) performer_->receive(m);
    midi::MidiPerformer::Round round = performer_->advance(seconds);
    for (const auto& refusal : round.refused()) nrt_say_midi(performer_->describe(refusal));
    if (round.refusals_lost > 0)
        nrt_say_midi(std::to_string(round.refusals_lost) +
                     " more messages refused in the same 2 ms");
    for (const auto& request : round.parameters()) {
        if (request.what == midi::ParameterRequest::What::BowPosition) {
            nrt_move_bow(request.value, std::nullopt);
            continue;
        }
        if (request.what == midi::ParameterRequest::What::Route &&
            unplayable_routes_.at(static_cast<std::size_t>(request.route)))
            continue;
        CommandFrame c{};
        c.opcode = static_cast<std::uint32_t>(Opcode::SetParameter);
        c.value = request.value;
        nrt_set_live_parameter(c, performer_->parameter_of(request));
    }
    if (round.bow_changed) {  // the real-time thread slides the bow on from where it is
        osc_hand_.press = round.press;
        CommandFrame drive{};
        drive.opcode = static_cast<std::uint32_t>(Opcode::Gesture);
        nrt_send({RealtimeCommand::BowDrive, {}, round.slide_speed, 0, round.press}, drive);
    }
}

}  // namespace archet
