// The engine's control thread playing from MIDI (midi_receiver.hpp): one member group of
// ControlThread, in a file of its own. The performer (core/midi) turns the messages into the
// hand's motion and parameter changes, which go the way the pad's and OSC's go: checked here,
// glided in on the real-time thread, recorded by a take.
#include <cstdio>
#include <map>

#include "control_thread.hpp"

namespace archet {

using namespace ipc;

// A performer for the model just loaded; a model MIDI cannot bow is
// said once and then not played from MIDI.
void ControlThread::nrt_prepare_performer() {
    performer_.reset();
    try {
        performer_.emplace(options_.midi_mapping, midi::performed_model(current_model_));
    } catch (const std::exception& e) {
        nrt_say_midi(std::string("this model is not played from MIDI: ") + e.what());
    }
}

void ControlThread::nrt_say_midi(const std::string& what) {
    std::fprintf(stderr, "archet engine: MIDI: %s\n", what.c_str());
    nrt_fail({}, "MIDI: " + what);
}

// The studio hears which controllers moved (the newest value of each this round): its MIDI
// learn assigns the one the player moves.
void ControlThread::nrt_show_controllers(const std::vector<midi::MidiMessage>& messages) {
    std::map<int, const midi::MidiMessage*> newest;
    for (const auto& m : messages) {
        if (m.kind == midi::MidiMessage::Kind::Control)
            newest[m.number] = &m;
        else if (m.kind == midi::MidiMessage::Kind::ChannelPressure)
            newest[midi::kChannelPressure] = &m;
    }
    for (const auto& [controller, m] : newest)
        publisher_.nrt_publish(StatusKind::Midi, static_cast<std::uint32_t>(controller),
                               midi::describe(*m));
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
    nrt_show_controllers(messages);
    if (!performer_) return;
    for (const auto& m : messages) performer_->receive(m);
    midi::MidiPerformer::Round round = performer_->advance(seconds);
    for (const auto& refusal : round.refused()) nrt_say_midi(performer_->describe(refusal));
    for (const auto& request : round.parameters()) {
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
