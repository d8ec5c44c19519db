#include "realtime_thread.hpp"

#include <algorithm>
#include <cmath>

#include "archet/common/denormal_guard.hpp"
#include "archet/engine/take_recorder.hpp"

namespace archet {

using namespace ipc;

RealtimeThread::RealtimeThread(ThreadBridge& bridge, SpscRing<ProbeFrame> probes,
                               SpscRing<ShapeFrame> shapes, const Setup& setup)
    : bridge_(bridge),
      rt_probes_(probes),
      rt_shapes_(shapes),
      sample_rate_(setup.sample_rate),
      shape_every_(setup.shape_every),
      has_haptic_device_(setup.has_haptic_device),
      fade_samples_(std::max(1, static_cast<int>(std::lround(kFadeSeconds * setup.sample_rate)))),
      rt_limiter_(std::make_unique<OutputLimiter>(setup.sample_rate)) {}

RealtimeThread::~RealtimeThread() {
    nrt_release_models();
}

void RealtimeThread::nrt_hand_back_takes() {
    if (rt_recording_) bridge_.finished_takes.ring().try_push(rt_recording_);
    if (rt_waiting_take_) bridge_.finished_takes.ring().try_push(rt_waiting_take_);
    rt_recording_ = rt_waiting_take_ = nullptr;
}

void RealtimeThread::nrt_release_models() {
    delete rt_fading_from_;
    rt_fading_from_ = nullptr;
    delete rt_running_;
    rt_running_ = nullptr;
}

void RealtimeThread::render(float* out, int frames, int channels) {
    rt_swap_in_pending();
    RealtimeCommand r;
    while (bridge_.to_realtime.ring().try_pop(r)) rt_apply(r);
    rt_silent_ = bridge_.silent.load(std::memory_order_relaxed);
    if (rt_muted_ || rt_silent_) rt_end_take();
    if (rt_waiting_take_ && !rt_silent_) rt_begin_take();
    if (rt_playing_ && rt_running_ && !rt_muted_ && !(rt_silent_ && rt_studio_gain_ <= 0))
        rt_run_block(*rt_running_, out, frames, channels);
    else
        std::fill(out, out + static_cast<std::ptrdiff_t>(frames) * channels, 0.0f);
    bridge_.blocks.fetch_add(1, std::memory_order_relaxed);
}

// A new model at a block boundary (not while one fades out, nor before the control thread took
// the last one let go of); the old one goes back for deletion.
void RealtimeThread::rt_swap_in_pending() {
    if (rt_fading_from_ || bridge_.retired.load(std::memory_order_acquire)) return;
    LoadedModel* next = bridge_.pending.exchange(nullptr, std::memory_order_acq_rel);
    if (!next) return;
    // The bow is where the hand holds it: the device's (or the pad's) position carries over.
    // Read before the old model is handed back for deletion.
    const GestureSample held = rt_running_ ? rt_running_->simulation->device_position() : rt_pad_;
    if (next->continues && rt_running_ && rt_continue_into(*next)) return;
    if (rt_running_ && rt_playing_ && !rt_muted_) {
        // Both play for a few milliseconds and cross-fade: no click.
        rt_fading_from_ = rt_running_;
        rt_fade_done_ = 0;
    } else {
        bridge_.retired.store(rt_running_, std::memory_order_release);
    }
    next->simulation->set_device_position(held);
    rt_end_take();  // the take's model is gone
    rt_running_ = next;
    rt_muted_ = false;
    rt_smoother_.clear();
    bridge_.swapped_sequence.store(next->sequence);
    bridge_.swaps.fetch_add(1, std::memory_order_release);
}

void RealtimeThread::rt_apply(const RealtimeCommand& r) {
    switch (r.kind) {
        case RealtimeCommand::Play:
            rt_playing_ = true;
            return;
        case RealtimeCommand::Stop:
            rt_playing_ = false;
            return;
        case RealtimeCommand::SetParameter: {
            // Its slots are the model's it was resolved for: another model drops it.
            if (!rt_running_ || r.generation != rt_running_->generation) return;
            Simulation& sim = *rt_running_->simulation;
            const int glide = static_cast<int>(kGlideSeconds * sim.sample_rate());
            rt_smoother_.glide(sim, r.slot, r.value, glide);
            if (rt_recording_) rt_recording_->parameter(sim.tick(), r.name, r.value, glide);
            // A take waiting to begin may begin while this glides: it must know its name.
            if (rt_waiting_take_ && r.named) rt_waiting_take_->name_slot_waiting(r.slot, r.name);
            return;
        }
        case RealtimeCommand::StartTake:
            if (rt_waiting_take_) bridge_.finished_takes.ring().try_push(rt_waiting_take_);
            rt_waiting_take_ = r.take;
            rt_waiting_generation_ = r.generation;
            return;
        case RealtimeCommand::StopTake:
            rt_end_take();
            return;
        case RealtimeCommand::Gesture:
            rt_pad_ = {r.slide, r.press};  // with a simulated hand the pad is its target
            rt_drive_speed_ = 0;
            if (rt_running_ && !has_haptic_device_)
                rt_running_->simulation->set_device_position(rt_pad_);
            return;
        case RealtimeCommand::BowDrive:
            rt_pad_.press = r.press;
            rt_drive_speed_ = r.value;
            if (rt_running_ && !has_haptic_device_)
                rt_running_->simulation->set_device_position(rt_pad_);
            return;
    }
}

// A take begins at a block boundary where the model plays alone: its saved state, its gesture
// and the glides under way (a fader that never rests keeps one going) then replay it exactly.
// Until then it waits.
void RealtimeThread::rt_begin_take() {
    if (rt_recording_ || !rt_running_ || rt_fading_from_) return;
    if (rt_running_->generation < rt_waiting_generation_) return;  // its model comes next
    if (rt_running_->generation > rt_waiting_generation_) {        // a newer model replaced it
        bridge_.finished_takes.ring().try_push(rt_waiting_take_);
        rt_waiting_take_ = nullptr;
        return;
    }
    Simulation& sim = *rt_running_->simulation;
    if (double* state = rt_waiting_take_->state_buffer()) sim.save_state(state);
    rt_waiting_take_->begin(sim.tick());
    rt_waiting_take_->gesture(sim.time(), sim.device_position());
    for (const ParameterSmoother::Glide& g : rt_smoother_.glides())
        rt_waiting_take_->glide_under_way(g);
    rt_recording_ = rt_waiting_take_;
    rt_waiting_take_ = nullptr;
}

void RealtimeThread::rt_end_take() {
    if (rt_recording_) bridge_.finished_takes.ring().try_push(rt_recording_);
    rt_recording_ = nullptr;
}

// Mixes the outgoing model into the incoming one's sample; retires it when faded out.
double RealtimeThread::rt_cross_fade(double incoming) {
    Simulation& old = *rt_fading_from_->simulation;
    old.step();
    const double outgoing = old.output();
    const double a = static_cast<double>(++rt_fade_done_) / fade_samples_;
    if (rt_fade_done_ >= fade_samples_ || !std::isfinite(outgoing)) {
        bridge_.retired.store(rt_fading_from_, std::memory_order_release);
        rt_fading_from_ = nullptr;
        return incoming;
    }
    return (1.0 - a) * outgoing + a * incoming;
}

// The same model with its bow elsewhere takes over the string's motion and the glides under way
// (its slots are the same): it plays on from here, no fade. A take recording on keeps the move
// as a change of "bow.position", which render --take makes the same way.
bool RealtimeThread::rt_continue_into(LoadedModel& next) {
    Simulation& from = *rt_running_->simulation;
    if (rt_fading_from_ || rt_muted_ || !next.simulation->continue_from(from, next.handover))
        return false;
    if (rt_recording_ && next.bow_move_named)
        rt_recording_->parameter(next.simulation->tick(), next.bow_move_name, next.bow_position, 1);
    else
        rt_end_take();
    bridge_.retired.store(rt_running_, std::memory_order_release);
    rt_running_ = &next;
    return true;
}

// The driven bow one haptic period on, where the gesture points read it next.
void RealtimeThread::rt_drive_bow(Simulation& sim, const LoadedModel& m) {
    rt_pad_.slide += rt_drive_speed_ * m.haptic_dt;
    if (!has_haptic_device_) sim.set_device_position(rt_pad_);
}

// The studio froze (fade out) or is back (fade in).
double RealtimeThread::rt_studio_fade(double output) {
    if (rt_silent_ ? rt_studio_gain_ > 0 : rt_studio_gain_ < 1) {
        rt_studio_gain_ += (rt_silent_ ? -1.0 : 1.0) / fade_samples_;
        rt_studio_gain_ = std::clamp(rt_studio_gain_, 0.0, 1.0);
    }
    return output * rt_studio_gain_;
}

// Silence from here to the block's end; the control thread resets the model.
void RealtimeThread::rt_mute(float* from, float* to) {
    rt_muted_ = true;
    bridge_.blown.store(true);
    std::fill(from, to, 0.0f);
}

// What happens before the step at the first tick of a run: the glides move on, the driven bow
// and the take's gesture at the hand's ticks, the haptic device.
void RealtimeThread::rt_before_run(Simulation& sim, LoadedModel& m) {
    rt_smoother_.advance(sim);
    if (rt_drive_speed_ != 0 && sim.tick() % m.haptic_divider == 0) rt_drive_bow(sim, m);
    if (m.haptic) m.haptic->before_step(sim, rt_pad_, rt_device_time());
    if (rt_recording_ && sim.tick() % m.haptic_divider == 0)  // the points read it now
        rt_recording_->gesture(sim.time() + m.haptic_dt, sim.device_position());
}

// How many ticks, up to `left`, run in one call from the current tick (after rt_before_run()):
// up to the next that asks for something before its step (a glide's, the hand's tick) or after
// it (the scopes' stored energy, which a take records at every tick and the run then reads),
// so that Simulation::run() takes a bowed string's own loop.
int RealtimeThread::rt_run_length(const Simulation& sim, const LoadedModel& m, int left) const {
    if (rt_smoother_.active() > 0) return 1;
    const std::uint64_t tick = sim.tick();
    std::uint64_t ticks = std::min<std::uint64_t>(left, kMostTicksARun);
    if (rt_drive_speed_ != 0 || rt_recording_)
        ticks = std::min(ticks, m.haptic_divider - tick % m.haptic_divider);
    if (m.haptic) ticks = std::min(ticks, m.haptic->ticks_to_link_tick(tick));
    if (m.has_energy_probe && !rt_recording_)
        ticks = std::min(ticks, kEnergyProbeEvery - tick % kEnergyProbeEvery);
    return static_cast<int>(ticks);
}

// The block in runs (rt_run_length()); after each tick, its probe frame, the take's sample,
// the cross-fade, the studio's fade and the limiter, as a tick at a time would.
void RealtimeThread::rt_run_block(LoadedModel& m, float* out, int frames, int channels) {
    const DenormalGuard no_denormals;
    Simulation& sim = *m.simulation;
    const std::size_t probes = sim.probe_count();
    float* const end = out + static_cast<std::ptrdiff_t>(frames) * channels;
    for (int i = 0; i < frames;) {
        rt_before_run(sim, m);
        const int length = rt_run_length(sim, m, frames - i);
        const std::uint64_t first = sim.tick();
        // A take records the stored energy at every tick: the run reads it then.
        const bool energy_each_tick = rt_recording_ != nullptr;
        const std::size_t ran = sim.run({rt_sound_.data(), static_cast<std::size_t>(length)},
                                        {.values = rt_rows_.data(), .energy = energy_each_tick});
        // A simulated hand moves on at each tick the run ran (it stops after one that is not
        // finite): the hand and the model read nothing of each other between the link's ticks.
        if (m.haptic)
            for (std::size_t k = 1; k < ran; ++k)
                m.haptic->between_link_ticks(
                    rt_pad_, static_cast<double>(rt_device_ticks_ + k) / sample_rate_,
                    1.0 / sim.sample_rate());
        rt_device_ticks_ += ran;
        for (std::size_t k = 0; k < ran; ++k, ++i) {
            ProbeFrame f;
            f.tick = first + k + 1;
            f.count = static_cast<std::uint32_t>(probes);
            f.reserved = 0;
            // The stored energy is a sum over every element, nearly as costly as the step: the
            // scopes get it at every ipc::kEnergyProbeEvery-th sample, where runs end, and hold
            // it in between; a take records it at every sample.
            const double* const row = rt_rows_.data() + k * probes;
            if (m.has_energy_probe && energy_each_tick)
                m.held_energy = row[m.energy_probe];
            else if (m.has_energy_probe && k + 1 == ran && f.tick % kEnergyProbeEvery == 0)
                m.held_energy = sim.stored_energy();
            for (std::size_t p = 0; p < probes; ++p)
                f.values[p] =
                    sim.model().probes[p].kind == ProbeKind::Energy ? m.held_energy : row[p];
            f.output = rt_sound_[k];
            // A take holds the model's own output, before the cross-fade and the studio's fade:
            // what `render --take` reproduces (a non-finite one ends the take, see TakeRecorder).
            if (rt_recording_)
                rt_recording_->sample(static_cast<double>(f.tick) / sim.sample_rate(), f.output,
                                      f.values, f.count);
            if (rt_fading_from_) f.output = rt_cross_fade(f.output);
            f.output = rt_studio_fade(f.output);
            if (!std::isfinite(f.output))
                return rt_mute(out + static_cast<std::ptrdiff_t>(i) * channels, end);
            const float y = rt_limiter_->process(f.output);
            for (int c = 0; c < channels; ++c) out[i * channels + c] = y;
            rt_probes_.try_push(f);
        }
    }
    bridge_.tick.store(sim.tick(), std::memory_order_relaxed);
    const double energy = sim.stored_energy();
    bridge_.energy.store(energy, std::memory_order_relaxed);
    const bool bowed = !sim.model().bows.empty();
    bridge_.bow_force.store(bowed ? sim.model().bows[0].normal : 0.0, std::memory_order_relaxed);
    bridge_.friction.store(bowed ? sim.model().bows[0].friction : 0.0, std::memory_order_relaxed);
    if (!std::isfinite(energy) || energy > kRunawayEnergy) return rt_mute(out, end);
    rt_publish_shape(m);
}

void RealtimeThread::rt_publish_shape(const LoadedModel& m) {
    if (++rt_shape_countdown_ < shape_every_) return;
    rt_shape_countdown_ = 0;
    const Simulation& sim = *m.simulation;
    ShapeFrame s;
    s.tick = sim.tick();
    s.count = static_cast<std::uint32_t>(m.shape.size());
    s.spread_over = m.shape_spread_over;
    for (std::size_t i = 0; i < m.shape.size(); ++i)
        s.positions[i] = static_cast<float>(sim.position(m.shape[i]));
    rt_shapes_.try_push(s);
}

}  // namespace archet
