// The engine's control thread answering OSC (osc_receiver.hpp): one member group of
// ControlThread, in a file of its own.
#include <cstdio>
#include <ctime>

#include "control_thread.hpp"

namespace archet {

using namespace ipc;

// What arrived since the last round. The hand's positions are coalesced: many OSC senders
// stream them far faster than the real-time thread's blocks, and only the newest matters.
void ControlThread::nrt_take_osc() {
    osc_hand_moved_ = false;
    for (const OscReceiver::Received& r : osc_->take()) {
        if (const auto* c = std::get_if<OscCommand>(&r)) {
            nrt_handle_osc(*c);
        } else {
            const std::string why = "OSC: " + std::get<std::string>(r);
            std::fprintf(stderr, "archet engine: %s\n", why.c_str());
            nrt_fail({}, why);
        }
    }
    if (osc_hand_moved_)
        nrt_send({RealtimeCommand::Gesture, {}, 0, osc_hand_.slide, osc_hand_.press}, {});
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
    switch (osc.kind) {
        case K::Slide:
            osc_hand_.slide = osc.value, osc_hand_moved_ = true;
            return;
        case K::Press:
            osc_hand_.press = osc.value, osc_hand_moved_ = true;
            return;
        case K::Finger:
        case K::FingerPressure: {
            const std::string finger = nrt_finger_id();
            if (finger.empty())
                return nrt_fail(c,
                                "OSC: /archet/finger: this model has no finger "
                                "(archet new bowed-string --finger adds one)");
            c.value = osc.value;
            return nrt_set_live_parameter(
                c, {finger, osc.kind == K::Finger ? "position" : "pressure"});
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

// The id of the loaded model's first finger, or empty.
std::string ControlThread::nrt_finger_id() const {
    for (const Lia& l : current_model_.lias)
        if (l.kind == LiaKind::Finger) return l.id;
    return {};
}

}  // namespace archet
