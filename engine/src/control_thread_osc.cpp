// The engine's control thread answering OSC (osc_receiver.hpp): one member group of
// ControlThread, in a file of its own.
#include <cstdio>
#include <ctime>
#include <set>

#include "control_thread.hpp"

namespace archet {

using namespace ipc;

namespace {

// How many refusals a round says one by one; the rest are counted in one sentence, so that a
// sender of garbage cannot flood the status ring.
constexpr int kRefusalsSaid = 8;

// What a command sets ("" for starts and stops, which all act): of the commands of one round
// that set the same thing, only the newest acts.
std::string target_of(const OscCommand& c) {
    using K = OscCommand::Kind;
    switch (c.kind) {
        case K::Parameter:
            return "param " + c.parameter.text();
        case K::RecordStart:
        case K::RecordStop:
            return "";
        default:
            return std::to_string(static_cast<int>(c.kind));
    }
}

// Which of `received` act: the newest of each target, every start and stop.
std::vector<bool> newest_of_each(const std::vector<OscReceiver::Received>& received) {
    std::vector<bool> acts(received.size(), true);
    std::set<std::string> later;
    for (std::size_t i = received.size(); i-- > 0;)
        if (const auto* c = std::get_if<OscCommand>(&received[i]))
            if (const std::string target = target_of(*c); !target.empty())
                acts[i] = later.insert(target).second;
    return acts;
}

}  // namespace

// What arrived since the last round. Senders stream positions and faders far faster than the
// real-time thread's blocks: of each axis, finger and parameter only the newest value acts
// (each is checked and glided in, and a take records it); starts and stops keep their order.
void ControlThread::nrt_take_osc() {
    osc_hand_moved_ = false;
    const std::vector<OscReceiver::Received> received = osc_->take();
    const std::vector<bool> acts = newest_of_each(received);
    int refused = 0;
    for (std::size_t i = 0; i < received.size(); ++i) {
        if (const auto* c = std::get_if<OscCommand>(&received[i])) {
            if (acts[i]) nrt_handle_osc(*c);
        } else if (++refused <= kRefusalsSaid) {
            const std::string why = "OSC: " + std::get<std::string>(received[i]);
            std::fprintf(stderr, "archet engine: %s\n", why.c_str());
            nrt_fail({}, why);
        }
    }
    if (refused > kRefusalsSaid)
        nrt_fail({}, "OSC: " + std::to_string(refused - kRefusalsSaid) +
                         " more messages refused in the same 2 ms");
    CommandFrame gesture{};
    gesture.opcode = static_cast<std::uint32_t>(Opcode::Gesture);
    if (osc_hand_moved_)
        nrt_send({RealtimeCommand::Gesture, {}, 0, osc_hand_.slide, osc_hand_.press}, gesture);
    if (const std::uint64_t dropped = osc_->dropped(); dropped > osc_dropped_said_) {
        osc_dropped_said_ = dropped;
        nrt_fail({}, "OSC: " + std::to_string(dropped) +
                         " messages dropped so far: they came faster than the engine reads them");
    }
}

// An OSC message, acted on as the studio's command of the same meaning would be; what is
// refused is said on the status ring (and stderr) and changes nothing.
void ControlThread::nrt_handle_osc(const OscCommand& osc) {
    CommandFrame c{};
    using K = OscCommand::Kind;
    c.opcode = static_cast<std::uint32_t>(osc.kind == K::RecordStart  ? Opcode::StartTake
                                          : osc.kind == K::RecordStop ? Opcode::StopTake
                                                                      : Opcode::SetParameter);
    switch (osc.kind) {
        case K::Slide:
            osc_hand_.slide = osc.value, osc_hand_moved_ = true;
            return;
        case K::Press:
            osc_hand_.press = osc.value, osc_hand_moved_ = true;
            return;
        case K::Finger:
        case K::FingerPressure: {
            const Lia* finger = first_finger(current_model_);
            if (!finger)
                return nrt_fail(c,
                                "OSC: /archet/finger: this model has no finger "
                                "(archet new bowed-string --finger adds one)");
            c.value = osc.value;
            return nrt_set_live_parameter(
                c, {finger->id, osc.kind == K::Finger ? "position" : "pressure"});
        }
        case K::Parameter:
            c.value = osc.value;
            return nrt_set_live_parameter(c, osc.parameter);
        case K::RecordStart: {
            if (take_root_.empty())
                return nrt_fail(c,
                                "OSC: /archet/record: the engine has no take directory "
                                "(start it with --takes DIR)");
            char stamp[32];
            const std::time_t now = std::time(nullptr);
            std::tm local{};
            std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", ::localtime_r(&now, &local));
            const auto folder =
                take_root_ / ("osc-" + std::string(stamp) + "-" + std::to_string(++osc_takes_));
            return nrt_start_take(c, folder.string());
        }
        case K::RecordStop:
            return nrt_send({RealtimeCommand::StopTake, {}, 0, 0, 0}, c);
    }
}

}  // namespace archet
