#include "archet/realtime_thread_mark.hpp"

namespace archet {

namespace {
thread_local bool realtime_thread = false;
}  // namespace

RealtimeThreadMark::RealtimeThreadMark() {
    realtime_thread = true;
}
RealtimeThreadMark::~RealtimeThreadMark() {
    realtime_thread = false;
}
void mark_realtime_thread() {
    realtime_thread = true;
}
bool on_realtime_thread() noexcept {
    return realtime_thread;
}

}  // namespace archet
