#include "archet/engine/realtime_engine.hpp"

#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <thread>
#include <variant>

#include "archet/common/denormal_guard.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/engine/take_recorder.hpp"
#include "archet/files/model_file.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/haptic_loop.hpp"
#include "archet/interruption.hpp"
#include "archet/ipc/command_decoder.hpp"
#include "archet/ipc/shared_segment.hpp"
#include "archet/ipc/take_folder.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/string_points.hpp"
#include "archet/output_limiter.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/parameter_smoother.hpp"
#include "archet/physics/simulation.hpp"
#include "archet/realtime_allocations.hpp"

namespace archet {

namespace {

using namespace ipc;

// A sanitizer's instrumented build runs the same code several times slower than the release
// build whose real-time behaviour the model-cost check judges: its measurements are scaled
// back by this much, so that CI under ThreadSanitizer accepts what a release engine plays.
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
constexpr double kInstrumentationSlowdown = 10;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer) || __has_feature(address_sanitizer)
constexpr double kInstrumentationSlowdown = 10;
#else
constexpr double kInstrumentationSlowdown = 1;
#endif
#else
constexpr double kInstrumentationSlowdown = 1;
#endif

// Everything the real-time thread needs of a model, built by the control thread.
struct LoadedModel {
    CompiledModel resolver;  ///< names → slots, on the control thread
    std::unique_ptr<Simulation> simulation;
    std::vector<MatSlot> shape;        ///< the string's MATs (string_points), in model order
    std::optional<HapticLoop> haptic;  ///< with a device: its loop and link for this model
    std::uint64_t haptic_divider = 1;  ///< the gesture points' level, for takes
    double haptic_dt = 0;
    std::uint64_t generation = 0;  ///< which load of the control thread it comes from
    std::uint32_t sequence = 0;
};

// Work the control thread hands to the real-time thread.
struct RealtimeCommand {
    enum Kind : std::uint32_t { SetParameter, Gesture, Play, Stop, StartTake, StopTake } kind;
    ParameterSlot slot;
    double value, slide, press;
    TakeRecorder* take = nullptr;  ///< StartTake: the recorder, owned by the real-time thread
    std::uint64_t generation = 0;  ///< StartTake: the model load it was prepared for
    std::uint32_t name = 0;        ///< SetParameter: its name in the take being recorded
};

std::string seconds_text(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f s", seconds);
    return text;
}

void copy_text(char (&to)[kTextSize], const std::string& from) {
    const std::size_t n = std::min(from.size(), kTextSize - 1);
    std::memcpy(to, from.data(), n);
    to[n] = '\0';
}

class Engine final : public AudioRenderer {
  public:
    Engine(SharedSegment segment, const EngineOptions& options, std::int32_t studio_pid)
        : segment_(std::move(segment)),
          options_(options),
          studio_pid_(studio_pid),
          commands_(segment_.commands()),
          probes_(segment_.probes()),
          shapes_(segment_.shapes()),
          status_(segment_.status()),
          to_realtime_(1024),
          finished_takes_(16) {}

    ~Engine() override {
        if (output_) output_->stop();
        if (studio_pidfd_ >= 0) ::close(studio_pidfd_);
    }

    int run() {
        auto& header = segment_.header();
        header.engine_pid.store(static_cast<std::int32_t>(::getpid()));
        watch_studio();
        std::string said = request_realtime_resources();
        if (!options_.takes.empty()) {
            try {
                take_root_ = prepare_take_directory(options_.takes);
            } catch (const std::exception& e) {
                take_problem_ = e.what();
                said += take_problem_ + "; ";
            }
        }
        haptic_ = open_haptic_device(options_.haptic);
        std::string warning;
        output_ = open_audio_output(options_.audio, &warning);
        sample_rate_ = output_->sample_rate();
        fade_samples_ = std::max(1, static_cast<int>(std::lround(kFadeSeconds * sample_rate_)));
        header.sample_rate.store(sample_rate_);
        limiter_ = std::make_unique<OutputLimiter>(sample_rate_);
        said +=
            output_->description() + ", " + std::to_string(output_->buffer_frames()) + " frames";
        if (!warning.empty()) said = warning + "; " + said;
        if (!haptic_.note.empty()) said += "; " + haptic_.note;
        output_->start(*this);
        said += "; " + output_->scheduling();
        header.engine_state.store(static_cast<std::uint32_t>(EngineState::Ready));
        publish(StatusKind::Heartbeat, 0, said);
        auto last_status = std::chrono::steady_clock::now();
        studio_beat_ = header.studio_heartbeat.load();
        studio_beat_at_ = last_watch_ = last_status;
        while (!quit_.load()) {
            header.engine_heartbeat.fetch_add(1);
            // SIGINT, SIGTERM, SIGHUP (InterruptionGuard) end the loop and the takes finish. For
            // the studio's child a signal may be the kernel's news that the studio died
            // (PR_SET_PDEATHSIG), or the terminal's Ctrl+C to the whole process group: the
            // studio's end is caught just below, or within the grace, since the death signal
            // comes when the studio's thread that started the engine exits, which can be a
            // moment before the whole process is gone. Still alive after it: a user's signal.
            const int signal = interruption_signal();
            if (signal && terminated_at_ == std::chrono::steady_clock::time_point{})
                terminated_at_ = std::chrono::steady_clock::now();
            if (studio_gone()) {
                // Nobody will read or unlink the segment: silence, clean up, leave.
                segment_.unlink();
                take_interruption_ = "the studio exited";
                break;
            }
            if (signal && (!child_of_studio_ ||
                           std::chrono::steady_clock::now() - terminated_at_ > kTerminateGrace))
                break;  // the studio lives: the segment is its to remove
            if (!watch_studio_heartbeat()) break;
            CommandFrame command;
            while (commands_.try_pop(command)) handle(command);
            collect_retired();
            collect_takes();
            if (blown_.exchange(false)) recover_from_blowup();
            if (std::chrono::steady_clock::now() - last_status > std::chrono::milliseconds(50)) {
                publish(StatusKind::Heartbeat, 0, current_name_);
                last_status = std::chrono::steady_clock::now();
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        header.engine_state.store(static_cast<std::uint32_t>(EngineState::Exiting));
        output_->stop();
        collect_retired();
        // The real-time thread has stopped: its takes are the control thread's to finish.
        if (recording_) finished_takes_.ring().try_push(recording_);
        if (waiting_take_) finished_takes_.ring().try_push(waiting_take_);
        recording_ = waiting_take_ = nullptr;
        const bool studio_exited = !take_interruption_.empty();
        const int signal = studio_exited ? 0 : interruption_signal();
        if (signal) take_interruption_ = signal_name(signal);
        collect_takes();
        delete pending_.exchange(nullptr);
        delete fading_from_;
        fading_from_ = nullptr;
        delete running_model_;
        running_model_ = nullptr;
        return signal ? 128 + signal : 0;
    }

    // ---- real-time thread: the device's callback ----------------------------------------

    void render(float* out, int frames, int channels) override {
        // A new model at a block boundary; the old one goes back for deletion.
        if (!fading_from_ && !retired_.load(std::memory_order_acquire)) {
            if (LoadedModel* next = pending_.exchange(nullptr, std::memory_order_acq_rel)) {
                // The bow is where the hand holds it: the device's (or the pad's) position
                // carries over. Read before the old model is handed back for deletion.
                const GestureSample held =
                    running_model_ ? running_model_->simulation->device_position() : pad_;
                if (running_model_ && playing_ && !muted_) {
                    // Both play for a few milliseconds and cross-fade: no click.
                    fading_from_ = running_model_;
                    fade_done_ = 0;
                } else {
                    retired_.store(running_model_, std::memory_order_release);
                }
                next->simulation->set_device_position(held);
                end_take();  // the take's model is gone
                running_model_ = next;
                muted_ = false;
                smoother_.clear();
                swapped_sequence_.store(next->sequence);
                swaps_.fetch_add(1, std::memory_order_release);
            }
        }
        RealtimeCommand r;
        while (to_realtime_.ring().try_pop(r)) {
            if (r.kind == RealtimeCommand::Play)
                playing_ = true;
            else if (r.kind == RealtimeCommand::Stop)
                playing_ = false;
            else if (running_model_ && r.kind == RealtimeCommand::SetParameter &&
                     r.generation == running_model_->generation) {  // its slots are this model's
                Simulation& sim = *running_model_->simulation;
                const int glide = static_cast<int>(kGlideSeconds * sim.sample_rate());
                smoother_.glide(sim, r.slot, r.value, glide);
                if (recording_) recording_->parameter(sim.tick(), r.name, r.value, glide);
            } else if (r.kind == RealtimeCommand::StartTake) {
                if (waiting_take_) finished_takes_.ring().try_push(waiting_take_);
                waiting_take_ = r.take;
                waiting_generation_ = r.generation;
            } else if (r.kind == RealtimeCommand::StopTake) {
                end_take();
            } else if (r.kind == RealtimeCommand::Gesture) {
                pad_ = {r.slide, r.press};  // with a simulated hand the pad is its target
                if (running_model_ && !haptic_.device)
                    running_model_->simulation->set_device_position(pad_);
            }
        }
        silent_now_ = silent_.load(std::memory_order_relaxed);
        if (muted_ || silent_now_) end_take();
        if (waiting_take_ && !silent_now_) begin_take();
        if (playing_ && running_model_ && !muted_ && !(silent_now_ && studio_gain_ <= 0))
            run_block(*running_model_, out, frames, channels);
        else
            std::fill(out, out + static_cast<std::ptrdiff_t>(frames) * channels, 0.0f);
        blocks_.fetch_add(1, std::memory_order_relaxed);
    }

  private:
    // ---- control thread ------------------------------------------------------------------

    // The studio's pid was fixed at start (later writes to the header change nothing). As its
    // child the engine asks the kernel for SIGTERM when it dies; in any case it holds a pidfd,
    // readable once the process has exited, or (without pidfd_open) asks kill(pid, 0).
    void watch_studio() {
        if (::getppid() == studio_pid_) {  // SIGTERM is handled by run_engine's guard
            ::prctl(PR_SET_PDEATHSIG, SIGTERM);
            child_of_studio_ = true;
        }
#ifdef SYS_pidfd_open
        studio_pidfd_ = static_cast<int>(::syscall(SYS_pidfd_open, studio_pid_, 0));
#endif
    }

    bool studio_gone() {
        if (child_of_studio_ && ::getppid() != studio_pid_) return true;  // died before prctl
        if (studio_pidfd_ >= 0) {
            pollfd p{studio_pidfd_, POLLIN, 0};
            return ::poll(&p, 1, 0) > 0;
        }
        return process_gone(studio_pid_);
    }

    // A studio whose heartbeat stops (frozen, stopped, stuck) cannot hear or steer: after
    // studio_timeout the sound fades out and nothing plays until it beats again; after
    // studio_give_up the engine leaves (a studio that wakes then restarts it). False: leave.
    bool watch_studio_heartbeat() {
        auto& header = segment_.header();
        const std::uint64_t beat = header.studio_heartbeat.load();
        const auto now = std::chrono::steady_clock::now();
        // A round far later than its 2 ms: the engine itself was stopped (Ctrl+Z stops the
        // studio's whole process group) and the studio, woken with it, has had no turn yet.
        if (now - last_watch_ > std::chrono::milliseconds(500)) studio_beat_at_ = now;
        last_watch_ = now;
        if (beat != studio_beat_) {
            studio_beat_ = beat;
            studio_beat_at_ = now;
            if (silenced_) {
                silenced_ = false;
                silent_.store(false);
                header.engine_state.store(static_cast<std::uint32_t>(EngineState::Ready));
                publish(StatusKind::Heartbeat, 0, "the studio beats again: playing");
            }
            return true;
        }
        const double quiet = std::chrono::duration<double>(now - studio_beat_at_).count();
        if (quiet > options_.studio_give_up) {
            publish(
                StatusKind::Error, 0,
                "the studio's heartbeat stopped " + seconds_text(quiet) + " ago: the engine exits");
            return false;
        }
        if (!silenced_ && quiet > options_.studio_timeout) {
            silenced_ = true;
            silent_.store(true);
            header.engine_state.store(static_cast<std::uint32_t>(EngineState::Silent));
            publish(StatusKind::Heartbeat, 0,
                    "silent: the studio's heartbeat stopped " + seconds_text(quiet) +
                        " ago; the sound comes back when it beats again");
        }
        return true;
    }

    std::string request_realtime_resources() {
        std::string said;
        if (!options_.lock_memory) return "memory not locked (not asked to); ";
        if (::mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
            said += "memory not locked (" + std::string(std::strerror(errno)) + "); ";
        else
            said += "memory locked; ";
        return said;
    }

    void publish(StatusKind kind, std::uint32_t sequence, const std::string& text) {
        StatusFrame f{};
        f.kind = static_cast<std::uint32_t>(kind);
        f.sequence = sequence;
        f.tick = tick_.load();
        f.blocks = blocks_.load();
        const AudioStats audio = output_ ? output_->stats() : AudioStats{};
        f.xruns = audio.xruns;
        f.dropped = probes_.dropped();
        f.load = measure_load(audio);
        f.worst_load =
            audio.callback_budget_us > 0 ? audio.worst_callback_us / audio.callback_budget_us : 0;
        f.sample_rate = sample_rate_;
        f.energy = energy_.load();
        f.realtime_allocations = realtime_allocations() + realtime_deallocations();
        copy_text(f.text, text);
        status_.try_push(f);
    }

    // The real-time thread's share of its budget: the time it spent rendering over the wall
    // time that passed, since the last measurement at least kLoadWindow ago (as JACK's DSP
    // load). One block the machine stalled in weighs as what it is, a moment, not forever.
    double measure_load(const AudioStats& audio) {
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

    void fail(const CommandFrame& c, const std::string& message) {
        publish(StatusKind::Error, c.sequence, message);
    }

    void handle(const CommandFrame& c) {
        const auto decoded = decode_command(c);  // every field checked: it came from outside
        if (const auto* why = std::get_if<std::string>(&decoded)) return fail(c, *why);
        const DecodedCommand& d = std::get<DecodedCommand>(decoded);
        switch (d.opcode) {
            case Opcode::LoadModel:
                return load(c, d.text);
            case Opcode::SetParameter:
                return set_live_parameter(c, d.parameter);
            case Opcode::Play:
                return send({RealtimeCommand::Play, {}, 0, 0, 0}, c);
            case Opcode::Stop:
                return send({RealtimeCommand::Stop, {}, 0, 0, 0}, c);
            case Opcode::Gesture:
                return send({RealtimeCommand::Gesture, {}, 0, d.slide, d.press}, c);
            case Opcode::Quit:
                quit_.store(true);
                return;
            case Opcode::StartTake:
                return start_take(c, d.text);
            case Opcode::StopTake:
                return send({RealtimeCommand::StopTake, {}, 0, 0, 0}, c);
        }
    }

    void send(const RealtimeCommand& r, const CommandFrame& c) {
        if (!to_realtime_.ring().try_push(r))
            fail(c, "the real-time thread is behind; command dropped");
    }

    // Compiles a validated model into what the real-time thread runs: off the real-time path.
    std::unique_ptr<LoadedModel> prepare(const Model& model, std::uint32_t sequence) const {
        auto loaded = std::make_unique<LoadedModel>();
        loaded->resolver = compile(model, sample_rate_);  // the device's clock is the master
        loaded->simulation = std::make_unique<Simulation>(loaded->resolver);
        loaded->simulation->set_gesture_track(nullptr);  // live: the device or the pad plays it
        if (haptic_.device)
            loaded->haptic.emplace(*haptic_.device, haptic_.hand, *loaded->simulation);
        if (const CompiledLevel* hand = hand_level(loaded->resolver))
            loaded->haptic_divider = static_cast<std::uint64_t>(hand->divider),
            loaded->haptic_dt = hand->dt;
        for (const std::string& id : string_points(model))
            if (loaded->shape.size() < kMaxShapePoints)
                loaded->shape.push_back(loaded->resolver.mat_slots.at(id));
        loaded->sequence = sequence;
        loaded->generation = generation_;  // a reset of the current model (load() counts a new one)
        return loaded;
    }

    void load(const CommandFrame& c, const std::string& path) {
        try {
            Model model = load_model_file(path);
            model.sample_rate = sample_rate_;  // it runs at the device's rate: checked at it
            validate_model(model);
            if (model.probes.size() > kMaxProbes)
                throw InputError(path, "has " + std::to_string(model.probes.size()) +
                                           " probes; the engine streams at most " +
                                           std::to_string(kMaxProbes));
            auto loaded = prepare(model, c.sequence);
            check_cost(path, *loaded);
            loaded->generation = ++generation_;  // only once it compiled
            current_resolver_ = loaded->resolver;
            current_model_ = std::move(model);
            current_name_ = current_model_.name;
            delete pending_.exchange(loaded.release());  // an unclaimed older one is dropped
        } catch (const std::exception& e) {
            fail(c, e.what());
        }
    }

    // Before a model is swapped in, a copy of it is stepped here, off the real-time path, for
    // at most kCostSamples samples or kCostSeconds: its fastest chunk's time per sample is
    // what the model needs at least. Above kCostShare of the device's time per sample it
    // cannot keep up (it would xrun on every block) and is refused.
    void check_cost(const std::string& path, const LoadedModel& loaded) const {
        const DenormalGuard no_denormals;
        Simulation copy(loaded.resolver);
        copy.set_gesture_track(nullptr);
        using clock = std::chrono::steady_clock;
        const auto start = clock::now();
        double best = std::numeric_limits<double>::infinity();  // s per sample
        for (int done = 0; done < kCostSamples;) {
            const auto t0 = clock::now();
            int n = 0;
            for (; n < kCostChunk && done + n < kCostSamples; ++n) copy.step();
            const auto t1 = clock::now();
            done += n;
            best = std::min(best, std::chrono::duration<double>(t1 - t0).count() / n);
            if (std::chrono::duration<double>(t1 - start).count() > kCostSeconds) break;
        }
        const double needs = best / kInstrumentationSlowdown, budget = 1.0 / sample_rate_;
        if (needs <= kCostShare * budget) return;
        const int block = output_->buffer_frames();
        char said[kTextSize];
        std::snprintf(said, sizeof said,
                      "cannot play in real time: this model needs %.3g ms per block of %d "
                      "frames, which lasts %.3g ms at %g Hz (over %d %% of one core); reduce the "
                      "masses and links",
                      needs * block * 1e3, block, budget * block * 1e3, sample_rate_,
                      static_cast<int>(kCostShare * 100));
        throw InputError(path, said);
    }

    void set_live_parameter(const CommandFrame& c, const ParameterName& name) {
        try {
            if (current_name_.empty()) throw InputError(name.text(), "no model is loaded");
            const ParameterSlot slot = current_resolver_.resolve_parameter(name);
            // The trust boundary: the studio checked the value, but commands come from another
            // process, and the engine runs at its device's rate. Range and stability, once.
            set_parameter_validated(current_model_, name, c.value);
            set_in_waiting_model(slot, c.value);
            RealtimeCommand r{RealtimeCommand::SetParameter, slot, c.value, 0, 0};
            r.generation = generation_;  // the real-time thread applies it to that model only
            if (live_take_) r.name = live_take_->parameter_name(name.text());
            send(r, c);
        } catch (const std::exception& e) {
            fail(c, e.what());
        }
    }

    // A model loaded but not yet swapped in was compiled before this change: it gets the value
    // here (the real-time thread leaves the command to the model it was resolved for).
    void set_in_waiting_model(const ParameterSlot& slot, double value) {
        LoadedModel* waiting = pending_.exchange(nullptr, std::memory_order_acq_rel);
        if (!waiting) return;  // none, or the real-time thread took it: the command will do
        waiting->simulation->write_slot(slot, value);
        delete pending_.exchange(waiting, std::memory_order_acq_rel);  // only this thread stores
    }

    // Opens the take's files here, off the real-time path, and hands the recorder over; the
    // real-time thread begins it at a block boundary.
    void start_take(const CommandFrame& c, const std::string& folder) {
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
            RealtimeCommand r{RealtimeCommand::StartTake, {}, 0, 0, 0};
            r.take = take.get();
            r.generation = generation_;
            if (!to_realtime_.ring().try_push(r))
                throw InputError(folder, "the real-time thread is behind; take not started");
            live_take_ = take.release();  // the real-time thread owns it until it hands it back
            publish(StatusKind::Take, c.sequence, "recording " + folder);
        } catch (const std::exception& e) {
            fail(c, e.what());
        }
    }

    // Finishes the takes the real-time thread handed back (ended, replaced or never begun).
    void collect_takes() {
        TakeRecorder* take = nullptr;
        while (finished_takes_.ring().try_pop(take)) {
            if (take == live_take_) live_take_ = nullptr;
            std::string said = "written " + take->folder().string();
            // Why the engine ended it early, if it did: take.json says so.
            std::string why = take_interruption_;
            if (why.empty() && blown_.load())
                why = "the model blew up (energy runaway or non-finite output) and was reset";
            if (why.empty() && silenced_) why = "the studio stopped answering";
            try {
                take->finish(why);
                said += " (" + std::to_string(take->frames()) + " samples";
                if (!why.empty()) said += ", interrupted: " + why;
                said += ")";
                // The live limiter kept the monitor clean; the take holds the raw output.
                if (take->clipped_samples() > 0) {
                    char peak[32];
                    std::snprintf(peak, sizeof peak, "%.2f", take->peak());
                    said += "; " + std::to_string(take->clipped_samples()) +
                            " samples clipped at full scale (peak " + peak +
                            "): " + gain_advice(take->peak());
                }
            } catch (const std::exception& e) {
                said = std::string("take failed: ") + e.what();
            }
            delete take;
            publish(StatusKind::Take, 0, said);
        }
    }

    // Deletes what the real-time thread let go of, and answers each model swap it made.
    void collect_retired() {
        delete retired_.exchange(nullptr, std::memory_order_acq_rel);
        const std::uint64_t swaps = swaps_.load(std::memory_order_acquire);
        if (swaps != swaps_answered_) {
            swaps_answered_ = swaps;
            publish(StatusKind::ModelLoaded, swapped_sequence_.load(), current_name_);
        }
    }

    void recover_from_blowup() {
        // The real-time thread muted the model; a fresh copy replaces it.
        delete pending_.exchange(prepare(current_model_, 0).release());
        publish(StatusKind::Blowup, 0,
                "energy runaway or non-finite output: muted within the block, model reset");
    }

    // ---- real-time thread ----------------------------------------------------------------

    // A take begins at a block boundary where the model plays alone and no parameter is
    // gliding: its saved state and gesture then replay it exactly. Until then it waits.
    void begin_take() {
        if (recording_ || !running_model_ || fading_from_ || smoother_.active() > 0) return;
        if (running_model_->generation < waiting_generation_) return;  // its model comes next
        if (running_model_->generation > waiting_generation_) {        // a newer model replaced it
            finished_takes_.ring().try_push(waiting_take_);
            waiting_take_ = nullptr;
            return;
        }
        Simulation& sim = *running_model_->simulation;
        if (double* state = waiting_take_->state_buffer()) sim.save_state(state);
        waiting_take_->begin(sim.tick());
        waiting_take_->gesture(sim.time(), sim.device_position());
        recording_ = waiting_take_;
        waiting_take_ = nullptr;
    }

    void end_take() {
        if (recording_) finished_takes_.ring().try_push(recording_);
        recording_ = nullptr;
    }

    // Mixes the outgoing model into the incoming one's sample; retires it when faded out.
    double cross_fade(double incoming) {
        Simulation& old = *fading_from_->simulation;
        old.step();
        const double outgoing = old.output();
        const double a = static_cast<double>(++fade_done_) / fade_samples_;
        if (fade_done_ >= fade_samples_ || !std::isfinite(outgoing)) {
            retired_.store(fading_from_, std::memory_order_release);
            fading_from_ = nullptr;
            return incoming;
        }
        return (1.0 - a) * outgoing + a * incoming;
    }

    double device_time() const {
        return static_cast<double>(device_ticks_) / sample_rate_;
    }

    void run_block(LoadedModel& m, float* out, int frames, int channels) {
        const DenormalGuard no_denormals;
        Simulation& sim = *m.simulation;
        const std::size_t probes = sim.probe_count();
        for (int i = 0; i < frames; ++i) {
            smoother_.advance(sim);
            if (m.haptic) m.haptic->before_step(sim, pad_, device_time());
            if (recording_ && sim.tick() % m.haptic_divider == 0)  // the points read it now
                recording_->gesture(sim.time() + m.haptic_dt, sim.device_position());
            sim.step();
            ++device_ticks_;
            ProbeFrame f;
            f.tick = sim.tick();
            f.count = static_cast<std::uint32_t>(probes);
            f.reserved = 0;
            for (std::size_t p = 0; p < probes; ++p) f.values[p] = sim.probe(p);
            f.output = sim.output();
            // A take holds the model's own output, before the cross-fade and the studio's fade:
            // what `render --take` reproduces (a non-finite one ends the take, see TakeRecorder).
            if (recording_) recording_->sample(sim.time(), f.output, f.values, f.count);
            if (fading_from_) f.output = cross_fade(f.output);
            if (silent_now_ ? studio_gain_ > 0
                            : studio_gain_ < 1) {  // the studio froze, or is back
                studio_gain_ += (silent_now_ ? -1.0 : 1.0) / fade_samples_;
                studio_gain_ = std::clamp(studio_gain_, 0.0, 1.0);
            }
            f.output *= studio_gain_;
            if (!std::isfinite(f.output)) {  // mute within this block; control resets the model
                muted_ = true;
                blown_.store(true);
                std::fill(out + static_cast<std::ptrdiff_t>(i) * channels,
                          out + static_cast<std::ptrdiff_t>(frames) * channels, 0.0f);
                return;
            }
            const float y = limiter_->process(f.output);
            for (int c = 0; c < channels; ++c) out[i * channels + c] = y;
            probes_.try_push(f);
        }
        tick_.store(sim.tick(), std::memory_order_relaxed);
        const double energy = sim.stored_energy();
        energy_.store(energy, std::memory_order_relaxed);
        if (!std::isfinite(energy) ||
            energy > kRunawayEnergy) {  // mute now; control resets the model
            muted_ = true;
            blown_.store(true);
            std::fill(out, out + static_cast<std::ptrdiff_t>(frames) * channels, 0.0f);
            return;
        }
        if (++shape_countdown_ >= options_.shape_every) {
            shape_countdown_ = 0;
            ShapeFrame s;
            s.tick = sim.tick();
            s.count = static_cast<std::uint32_t>(m.shape.size());
            s.reserved = 0;
            for (std::size_t i = 0; i < m.shape.size(); ++i)
                s.positions[i] = static_cast<float>(sim.position(m.shape[i]));
            shapes_.try_push(s);
        }
    }

    SharedSegment segment_;
    EngineOptions options_;
    const std::int32_t studio_pid_;                        ///< fixed at start
    std::chrono::steady_clock::time_point terminated_at_;  ///< when a signal was first seen
    std::chrono::steady_clock::time_point last_watch_;     ///< the previous heartbeat check
    static constexpr std::chrono::milliseconds kTerminateGrace{500};
    int studio_pidfd_ = -1;          ///< readable once the studio has exited (-1: none)
    bool child_of_studio_ = false;   ///< the kernel sends SIGTERM when the studio dies
    std::uint64_t studio_beat_ = 0;  ///< control thread: the studio's heartbeat as last seen
    std::chrono::steady_clock::time_point studio_beat_at_;  ///< when it last moved
    bool silenced_ = false;                                 ///< control thread
    std::atomic<bool> silent_{false};  ///< control → real-time: the studio froze, play nothing
    bool silent_now_ = false;          ///< real-time thread: silent_ for this block
    double studio_gain_ = 1;           ///< real-time thread: fades out while silent, back in after
    std::filesystem::path take_root_;  ///< canonical take directory (empty: no takes)
    std::string take_problem_;         ///< why the take directory could not be used
    static constexpr int kCostSamples = 2048, kCostChunk = 8;
    static constexpr double kCostSeconds = 0.02, kCostShare = 0.7;
    SpscRing<CommandFrame> commands_;
    SpscRing<ProbeFrame> probes_;
    SpscRing<ShapeFrame> shapes_;
    SpscRing<StatusFrame> status_;
    LocalRing<RealtimeCommand> to_realtime_;
    LocalRing<TakeRecorder*> finished_takes_;  ///< real-time → control: takes to finish
    std::unique_ptr<AudioOutput> output_;
    std::unique_ptr<OutputLimiter> limiter_;
    std::atomic<bool> quit_{false}, blown_{false};
    std::atomic<LoadedModel*> pending_{nullptr}, retired_{nullptr};
    std::atomic<std::uint32_t> swapped_sequence_{0};
    std::atomic<std::uint64_t> swaps_{0};
    std::uint64_t swaps_answered_ = 0;      ///< control thread
    LoadedModel* running_model_ = nullptr;  ///< owned by the real-time thread while it runs
    bool muted_ = false, playing_ = false;  ///< real-time thread only
    int shape_countdown_ = 0;               ///< real-time thread only
    /// Real-time thread: samples played since the engine started, whatever the model. The
    /// device's clock: a new model's own time starts again at 0, the device's does not.
    std::uint64_t device_ticks_ = 0;
    GestureSample pad_{};                   ///< real-time thread: the pad's latest position
    TakeRecorder* waiting_take_ = nullptr;  ///< real-time thread: to begin when it can
    std::uint64_t waiting_generation_ = 0;  ///< real-time thread: the model it was made for
    TakeRecorder* recording_ = nullptr;     ///< real-time thread: the take being fed
    TakeRecorder* live_take_ = nullptr;     ///< control thread: the take it last started
    std::string take_interruption_;         ///< control thread: why takes end early, if they do
    HapticChoice haptic_;         ///< the device, used by the real-time thread (none by default)
    ParameterSmoother smoother_;  ///< real-time thread only
    static constexpr double kGlideSeconds = 0.01;  ///< parameter changes arrive over 10 ms
    LoadedModel* fading_from_ = nullptr;           ///< real-time thread: the model being faded out
    int fade_done_ = 0;
    static constexpr double kFadeSeconds = 0.01;  ///< models swap over a 10 ms cross-fade
    int fade_samples_ = 1;                        ///< kFadeSeconds at the device's rate
    double sample_rate_ = 48000;  ///< the device's clock, the master: set once it is open
    /// A bowed string holds millijoules: a thousand joules means the numbers ran away.
    static constexpr double kRunawayEnergy = 1e3;
    std::atomic<std::uint64_t> tick_{0}, blocks_{0};
    // Control thread: the load's last measurement.
    static constexpr double kLoadWindowUs = 200'000;
    std::chrono::steady_clock::time_point load_measured_at_{};
    double load_busy_us_ = 0, load_ = 0;
    std::atomic<double> energy_{0};
    // Control thread's view of the model, for names and checks.
    Model current_model_;
    CompiledModel current_resolver_;
    std::string current_name_;
    std::uint64_t generation_ = 0;  ///< control thread: models loaded so far
};

}  // namespace

int run_engine(const EngineOptions& options) {
    // SIGINT, SIGTERM, SIGHUP end the loop and the takes finish; a second one too (the
    // studio's death signal and a terminal's may both come) leaves the clean-up to finish.
    const InterruptionGuard stop_on_signal(/*second_ends_at_once=*/false);
    ipc::SharedSegment segment = ipc::SharedSegment::attach(options.segment);
    // Read once: whatever is written into the header later, this is the studio watched.
    const std::int32_t studio_pid =
        options.studio_pid > 0 ? options.studio_pid : segment.header().studio_pid;
    if (studio_pid <= 1)
        throw InputError("segment " + options.segment,
                         "names no studio process (owner pid " + std::to_string(studio_pid) +
                             "): give the studio's pid with --studio-pid");
    if (!options.takes.empty() && !std::filesystem::path(options.takes).is_absolute())
        throw InputError("--takes " + quoted_text(options.takes),
                         "the take directory must be an absolute path");
    Engine engine(std::move(segment), options, studio_pid);
    return engine.run();
}

}  // namespace archet
