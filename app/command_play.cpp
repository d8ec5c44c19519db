// `archet play`: plays a model live, without the studio: the gesture file (or the model's own)
// drives the device axes, the sound goes to an audio device or the null sink, and --stats
// reports how the real-time thread kept up.

#include <time.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "archet/audio_output.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/monotonic_clock.hpp"
#include "archet/engine/take_recorder.hpp"
#include "archet/files/model_file.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/haptic_loop.hpp"
#include "archet/interruption.hpp"
#include "archet/midi_ports.hpp"
#include "archet/output_limiter.hpp"
#include "archet/physics/chain_build_choice.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "archet/realtime_allocations.hpp"
#include "archet/simulated_hand.hpp"
#include "audio_options.hpp"
#include "commands.hpp"
#include "live_play.hpp"
#include "model_loading.hpp"
#include "option_checks.hpp"

namespace archet::cli {

namespace {

struct PlayArguments {
    std::string model, gesture, haptic = "none", take;
    AudioConfig audio;
    double duration = 0;
    bool stats = false;
    int osc_port = 0;
    std::string midi, midi_api = "alsa", midi_map;
};

// With OSC or MIDI the model is played live through the engine (live_play.hpp).
int run_live(const PlayArguments& a) {
    if (!a.gesture.empty())
        throw InputError("--gesture",
                         "plays a file; with --osc or --midi the players play it "
                         "(give one or the other)");
    if (a.stats)
        throw InputError("--stats", "is for a gesture file's run, not with --osc or --midi");
    LivePlayArguments live;
    live.model = a.model, live.audio = a.audio, live.haptic = a.haptic, live.take = a.take;
    live.duration = a.duration, live.osc_port = a.osc_port;
    live.midi = a.midi, live.midi_api = a.midi_api, live.midi_map = a.midi_map;
    return run_live_play(live);
}

// The real-time side of `play`: fills the device's buffer a block at a time, running the model
// in runs of ticks up to the hand's next (so that a bowed string runs its own loop).
class Player final : public AudioRenderer {
  public:
    Player(Simulation& sim, double budget_ns, const Gesture* gesture, const HapticChoice& haptic,
           TakeRecorder* take)
        : sim_(sim),
          limiter_(sim.sample_rate()),
          budget_ns_(budget_ns),
          gesture_(gesture),
          take_(take) {
        if (haptic.device) haptic_loop_.emplace(*haptic.device, haptic.hand, sim);
        if (const CompiledLevel* hand = hand_level(sim.model()))
            haptic_divider_ = static_cast<std::uint64_t>(hand->divider), haptic_dt_ = hand->dt;
        if (take_) take_->gesture(0.0, played(0.0));  // where the gesture points start
    }

    void render(float* out, int frames, int channels) override {
        const DenormalGuard no_denormals;
        const std::int64_t start = monotonic_ns();
        const std::uint64_t first = sim_.tick();
        for (int i = 0; i < frames;) {
            before_run();
            const std::size_t length = run_length(frames - i);
            const std::size_t ran =
                take_ ? sim_.run({sound_.data(), length}, {.values = rows_.data(), .energy = true})
                      : sim_.run({sound_.data(), length});
            // A simulated hand moves on at each tick the run ran: it and the model read nothing
            // of each other between the link's ticks (HapticLoop::between_link_ticks()).
            if (haptic_loop_)
                for (std::size_t k = 1; k < ran; ++k) {
                    const double t =
                        static_cast<double>(sim_.tick() - ran + k) / sim_.sample_rate();
                    haptic_loop_->between_link_ticks(target(t), t, 1.0 / sim_.sample_rate());
                }
            for (std::size_t k = 0; k < ran; ++k, ++i) {
                if (take_) {
                    const std::uint64_t tick = sim_.tick() - ran + k + 1;
                    take_->sample(static_cast<double>(tick) / sim_.sample_rate(), sound_[k],
                                  rows_.data() + k * sim_.probe_count(), sim_.probe_count());
                }
                const float y = limiter_.process(sound_[k]);
                for (int c = 0; c < channels; ++c) out[i * channels + c] = y;
            }
        }
        // Ticks of the haptic level (the gesture link) in this block, and whether the block was
        // late: rendering it took longer than it lasts.
        const std::uint64_t ticks = (sim_.tick() + haptic_divider_ - 1) / haptic_divider_ -
                                    (first + haptic_divider_ - 1) / haptic_divider_;
        haptic_ticks_.fetch_add(ticks, std::memory_order_relaxed);
        if (static_cast<double>(monotonic_ns() - start) > budget_ns_)
            haptic_late_.fetch_add(ticks, std::memory_order_relaxed);
    }

    std::uint64_t haptic_ticks() const { return haptic_ticks_.load(); }
    std::uint64_t haptic_late_ticks() const { return haptic_late_.load(); }
    const OutputLimiter& limiter() const { return limiter_; }

  private:
    // Before the first tick of a run: the haptic device, and the take's gesture at the hand's
    // ticks (the gesture points read their next position then, at time + their period).
    void before_run() {
        // One model for the whole performance: its time is the device's clock.
        if (haptic_loop_) haptic_loop_->before_step(sim_, target(sim_.time()), sim_.time());
        if (take_ && sim_.tick() % haptic_divider_ == 0) {
            const double t_next = sim_.time() + haptic_dt_;
            take_->gesture(t_next, played(t_next));
        }
    }
    // How many ticks, up to `left`, run in one call of Simulation::run() (so that a bowed string
    // runs its own loop): up to the next tick at which the haptic link or the take's gesture
    // read something before the step.
    std::size_t run_length(int left) const {
        std::uint64_t ticks = std::min<std::uint64_t>(left, kMostTicksARun);
        if (haptic_loop_) ticks = std::min(ticks, haptic_loop_->ticks_to_link_tick(sim_.tick()));
        if (take_) ticks = std::min(ticks, haptic_divider_ - sim_.tick() % haptic_divider_);
        return ticks;
    }
    // Where a simulated hand is asked to go at t: the gesture file, else nowhere.
    GestureSample target(double t) const { return gesture_ ? gesture_->at(t) : GestureSample{}; }

    static constexpr std::uint64_t kMostTicksARun = 64;
    Simulation& sim_;
    std::array<double, kMostTicksARun> sound_{};
    std::vector<double> rows_ =
        std::vector<double>(kMostTicksARun * sim_.probe_count());  ///< probes
    OutputLimiter limiter_;
    double budget_ns_;
    std::uint64_t haptic_divider_ = 1;  ///< the gesture points' level (see hand_level())
    // What the gesture points read at t: the device with a hand on it, else the gesture file.
    GestureSample played(double t) const {
        return haptic_loop_ || !gesture_ ? sim_.device_position() : gesture_->at(t);
    }

    const Gesture* gesture_;
    TakeRecorder* take_;
    double haptic_dt_ = 1.0 / sim_.sample_rate();
    std::optional<HapticLoop> haptic_loop_;
    std::atomic<std::uint64_t> haptic_ticks_{0}, haptic_late_{0};
};

int run_play(const PlayArguments& a) {
    if (a.osc_port > 0 || !a.midi.empty()) return run_live(a);
    const InterruptionGuard stop_on_signal;  // SIGINT, SIGTERM, SIGHUP: stop and finish the take
    if (a.duration < 0 || !std::isfinite(a.duration))
        throw InputError("--duration", "must be positive seconds");
    const Model model = load_validated_model(a.model, {});
    std::optional<Gesture> gesture;
    if (!a.gesture.empty())
        gesture = load_gesture_file(a.gesture);
    else if (model.gesture)
        gesture = model.gesture;

    std::string warning;
    auto output = open_audio_output(a.audio, &warning);
    if (!warning.empty()) std::cerr << "archet: warning: " << warning << "\n";
    // The device's clock is the master clock: the model runs at its rate.
    Simulation sim(compile(model, output->sample_rate()));
    const HapticChoice haptic = open_haptic_device(a.haptic);
    if (!haptic.note.empty()) std::cerr << "archet play: " << haptic.note << "\n";
    // Without a device the gesture file plays the gesture points directly; with one, it moves
    // the hand that holds the device.
    sim.set_gesture_track(gesture && !haptic.device ? &*gesture : nullptr);
    sim.set_chain_build(fastest_chain_build(sim));
    std::unique_ptr<TakeRecorder> take;
    if (!a.take.empty()) {
        std::vector<std::string> probes;
        for (const auto& p : sim.model().probes) probes.push_back(p.id);
        take = std::make_unique<TakeRecorder>(a.take, model, sim.sample_rate(), probes);
        take->begin(0);  // from the model's start: no state needed to re-render it
    }
    Player player(sim, 1e9 * output->buffer_frames() / output->sample_rate(),
                  gesture ? &*gesture : nullptr, haptic, take.get());
    const double duration =
        a.duration > 0 ? a.duration : (gesture ? gesture->duration() + 0.5 : 5.0);
    std::cerr << "archet: playing " << model.name << " on " << output->description() << ", "
              << output->buffer_frames() << " frames at " << output->sample_rate() << " Hz for "
              << duration << " s\n";
    const std::uint64_t allocations_before = realtime_allocations();
    output->start(player);
    std::cerr << "archet: " << output->scheduling() << "\n";
    // Plays until the duration is over or a signal asks to stop.
    const auto end = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(duration));
    for (auto now = std::chrono::steady_clock::now(); now < end && !interruption_signal();
         now = std::chrono::steady_clock::now())
        std::this_thread::sleep_for(std::min<std::chrono::steady_clock::duration>(
            end - now, std::chrono::milliseconds(10)));
    const int signal = interruption_signal();
    output->stop();
    std::string incomplete;  // why the take holds less than was played
    if (take) {
        take->finish(signal ? signal_name(signal) : "");
        incomplete = take->incomplete_note();
        std::cerr << "archet: take written to " << take->folder().string()
                  << " (take.wav, gesture.json, probes.csv";
        if (incomplete.empty())
            std::cerr << "; `archet render --take " << take->folder().string()
                      << " -o FILE` re-renders it";
        std::cerr << ")\n";
        if (signal)
            std::cerr << "archet: the take was interrupted by " << signal_name(signal) << " after "
                      << static_cast<double>(take->frames()) / sim.sample_rate()
                      << " s; take.json says so\n";
        if (const std::string note = take->clipping_note(); !note.empty())
            std::cerr << "archet: warning: " << note << "\n";
        if (!incomplete.empty()) std::cerr << "archet: error: " << incomplete << "\n";
    }
    if (a.stats) {
        const AudioStats s = output->stats();
        const nlohmann::ordered_json stats{
            {"callbacks", s.callbacks},
            {"xruns", s.xruns},
            {"worst_callback_us", s.worst_callback_us},
            {"callback_budget_us", s.callback_budget_us},
            {"haptic_ticks", player.haptic_ticks()},
            {"haptic_late_ticks", player.haptic_late_ticks()},
            {"realtime_allocations", realtime_allocations() - allocations_before},
            {"limited_samples", player.limiter().limited()},
            {"output", output->description()}};
        std::cout << stats.dump() << "\n";
    }
    if (signal) {
        std::cerr << "archet: interrupted by " << signal_name(signal) << "\n";
        return 128 + signal;
    }
    return incomplete.empty() ? 0 : 1;  // a take that lost samples is not what was asked
}

}  // namespace

void add_play_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<PlayArguments>();
    auto* cmd = app.add_subcommand(
        "play", "Play a model live, without the studio (gesture file as the device)");
    cmd->add_option("model", a->model, "Model file (.json)")->required();
    add_audio_options(*cmd, a->audio);
    cmd->add_option("--haptic", a->haptic,
                    "Haptic device: none, sim (a simulated hand following the gesture), evdev:PATH "
                    "(a force-feedback joystick) or sdl:INDEX (an SDL joystick)")
        ->capture_default_str();
    cmd->add_option("--take", a->take,
                    "Record a take into this new folder: take.wav, gesture.json, probes.csv");
    cmd->add_option("--gesture", a->gesture,
                    "Gesture file playing the device axes (default: the model's)");
    cmd->add_option("--duration", a->duration, "Seconds to play (default: gesture + 0.5 s, or 5 s)")
        ->check(duration_range(limits::kDurationSeconds));
    cmd->add_flag("--stats", a->stats,
                  "Print JSON at the end: callbacks, xruns, worst_callback_us, callback_budget_us, "
                  "haptic_ticks, "
                  "haptic_late_ticks");
    cmd->add_option("--osc", a->osc_port,
                    "Play it live from OSC on this UDP port (loopback), through the engine")
        ->check(CLI::Range(1, 65535));
    cmd->add_option(
           "--midi", a->midi,
           "Play it live from MIDI, through the engine: virtual (a port archet-midi:midi_in) "
           "or a part of a source's name (archet devices lists them)")
        ->expected(0, 1)
        ->default_str("virtual");
    cmd->add_option("--midi-api", a->midi_api, "Where MIDI comes from: alsa or jack")
        ->check(CLI::IsMember({"alsa", "jack"}))
        ->capture_default_str();
    cmd->add_option(
        "--midi-map", a->midi_map,
        "How MIDI plays the model: a mapping file (default: STK's Bowed's controllers)");
    cmd->callback([&action, a] { action = [a] { return run_play(*a); }; });
}

void add_devices_command(CLI::App& app, Action& action) {
    auto* cmd = app.add_subcommand(
        "devices", "List the audio outputs, haptic devices and MIDI sources Archet can play with");
    cmd->callback([&action] {
        action = [] {
            for (const AudioApiDevices& api : list_audio_devices())
                for (const std::string& line : describe(api)) std::cout << line << "\n";
            // A backend that found nothing says where it looked; the simulated hand is always
            // there.
            const std::pair<std::string, const char*> backends[] = {
                {"evdev",
                 "evdev: no force-feedback joystick found in /dev/input (readable event devices "
                 "with two absolute axes and FF_CONSTANT)"},
                {"sdl", "sdl: no joystick found by SDL"},
                {"sim", ""}};
            const std::vector<HapticDeviceInfo> haptic = list_haptic_choices();
            for (const auto& [backend, none] : backends) {
                bool found = false;
                for (const HapticDeviceInfo& d : haptic)
                    if (d.backend == backend) std::cout << describe(d) << "\n", found = true;
                if (!found) std::cout << none << "\n";
            }
            // MIDI sources, under the names --midi takes (any part of one).
            for (const std::string& api : midi_apis()) {
                const std::vector<std::string> ports = list_midi_inputs(api);
                for (const std::string& port : ports)
                    std::cout << "midi " << api << ": " << port << "\n";
                if (ports.empty()) std::cout << "midi " << api << ": no MIDI source found\n";
            }
            return 0;
        };
    });
}

}  // namespace archet::cli
