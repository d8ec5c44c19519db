#include "status_publisher.hpp"

#include <algorithm>
#include <cstring>

#include "archet/realtime_allocations.hpp"

namespace archet {

using namespace ipc;

namespace {
void copy_text(char (&to)[kTextSize], const std::string& from) {
    const std::size_t n = std::min(from.size(), kTextSize - 1);
    std::memcpy(to, from.data(), n);
    to[n] = '\0';
}
}  // namespace

void StatusPublisher::nrt_publish(StatusKind kind, std::uint32_t sequence,
                                  const std::string& text) {
    StatusFrame f{};
    f.kind = static_cast<std::uint32_t>(kind);
    f.sequence = sequence;
    f.tick = bridge_.tick.load();
    f.blocks = bridge_.blocks.load();
    const AudioStats audio = output_ ? output_->stats() : AudioStats{};
    f.xruns = audio.xruns;
    f.dropped = probes_.dropped();
    f.load = nrt_measure_load(audio);
    f.worst_load =
        audio.callback_budget_us > 0 ? audio.worst_callback_us / audio.callback_budget_us : 0;
    f.energy = bridge_.energy.load();
    f.realtime_allocations = realtime_allocations() + realtime_deallocations();
    copy_text(f.text, text);
    status_.try_push(f);
}

// The real-time thread's share of its budget: the time it spent rendering over the wall time
// that passed, since the last measurement at least kLoadWindow ago (as JACK's DSP load). One
// block the machine stalled in weighs as what it is, a moment, not forever.
double StatusPublisher::nrt_measure_load(const AudioStats& audio) {
    const auto now = std::chrono::steady_clock::now();
    const double elapsed_us =
        std::chrono::duration<double, std::micro>(now - load_measured_at_).count();
    if (elapsed_us >= kLoadWindowUs) {
        if (load_measured_at_ != std::chrono::steady_clock::time_point{})
            load_ = (audio.busy_us - load_busy_us_) / elapsed_us;
        load_measured_at_ = now;
        load_busy_us_ = audio.busy_us;
    }
    return load_;
}

}  // namespace archet
