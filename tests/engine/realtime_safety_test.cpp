// Real-time code never allocates, frees, locks or does I/O. Proven by counting, on the threads
// marked real-time, every such call the process makes (realtime_interposer.hpp): first that
// each kind of call is seen when a marked thread makes it, then that none is made by
// Simulation::step, nor by the engine's real-time thread over a whole session run in this
// process through its real code (run_engine on a null sink): playing, bowing a simulated hand
// through the haptic loop, parameters gliding through the smoother, takes recorded, models
// swapped with a cross-fade, and a blow-up muted.

#include <gtest/gtest.h>
#include <malloc.h>
#include <pthread.h>
#include <time.h>
#include <unistd.h>

#include <fcntl.h>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <mutex>
#include <new>
#include <set>
#include <shared_mutex>
#include <string>
#include <thread>
#include <vector>

#include "archet/builders/bowed_string.hpp"
#include "archet/engine/realtime_engine.hpp"
#include "archet/link/engine_link.hpp"
#include "archet/model/string_points.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/modal_point_position.hpp"
#include "archet/physics/simulation.hpp"
#include "archet/realtime_allocations.hpp"
#include "realtime_interposer.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using namespace std::chrono_literals;
using test::realtime_calls;
using test::RealtimeCall;
using test::RealtimeCalls;

// A function pointer the optimiser cannot see through: the call is made, not elided.
template <class F>
F* opaque(F* f) {
    F* volatile v = f;
    return v;
}

// Runs `marked` on a new thread while it is marked real-time, then `after` unmarked; returns
// what was counted meanwhile (no other thread is marked then).
RealtimeCalls counted_on_marked_thread(
    const std::function<void()>& marked, const std::function<void()>& after = [] {}) {
    const RealtimeCalls before = realtime_calls();
    std::thread([&] {
        {
            const RealtimeThreadMark mark;
            marked();
        }
        after();
    }).join();
    return realtime_calls() - before;
}

struct ForbiddenCall {
    const char* what;
    RealtimeCall by_name;        ///< the kind it is counted as
    bool c_allocator;            ///< malloc to free: by the sanitizer's hooks, under one
    bool frees;                  ///< (then as SanitizerFree, else SanitizerAllocation)
    std::function<void()> call;  ///< on the marked thread
    std::function<void()> undo;  ///< after, unmarked
};

std::vector<ForbiddenCall> controls() {
    static void* p = nullptr;
    static int fd = -1;
    static FILE* file = nullptr;
    static char buffer[8];
    auto release = [] { std::free(p), p = nullptr; };
    using Alloc = void*(std::size_t);
    using AlignedAlloc = void*(std::size_t, std::align_val_t);
    using NothrowAlloc = void*(std::size_t, const std::nothrow_t&);
    using AlignedNothrowAlloc = void*(std::size_t, std::align_val_t, const std::nothrow_t&);
    constexpr auto a = std::align_val_t{64};
    const auto undo_new = [] { ::operator delete(p), p = nullptr; };
    const auto undo_aligned_new = [] { ::operator delete (p, std::align_val_t{64}), p = nullptr; };
    return {
        {"malloc", RealtimeCall::Malloc, true, false, [] { p = opaque(&std::malloc)(8); }, release},
        {"calloc", RealtimeCall::Calloc, true, false, [] { p = opaque(&std::calloc)(2, 8); },
         release},
        {"realloc", RealtimeCall::Realloc, true, false, [] { p = opaque(&std::realloc)(p, 4096); },
         release},
        {"free", RealtimeCall::Free, true, true,
         [] { opaque (&std::free)(opaque(&std::malloc)(8)); }, [] {}},
        {"posix_memalign", RealtimeCall::PosixMemalign, false, false,
         [] { (void)opaque (&::posix_memalign)(&p, 64, 64); }, release},
        {"aligned_alloc", RealtimeCall::AlignedAlloc, false, false,
         [] { p = opaque(&std::aligned_alloc)(64, 64); }, release},
        {"memalign", RealtimeCall::Memalign, false, false, [] { p = opaque(&::memalign)(64, 64); },
         release},
        {"valloc", RealtimeCall::Valloc, false, false, [] { p = opaque(&::valloc)(64); }, release},
        {"operator new", RealtimeCall::OperatorNew, false, false,
         [] { p = opaque(static_cast<Alloc*>(&::operator new))(8); }, undo_new},
        {"operator new[]", RealtimeCall::OperatorNew, false, false,
         [] { p = opaque(static_cast<Alloc*>(&::operator new[]))(8); },
         [] { ::operator delete[](p), p = nullptr; }},
        {"aligned operator new", RealtimeCall::OperatorNew, false, false,
         [] { p = opaque(static_cast<AlignedAlloc*>(&::operator new))(8, std::align_val_t{64}); },
         undo_aligned_new},
        {"aligned operator new[]", RealtimeCall::OperatorNew, false, false,
         [] { p = opaque(static_cast<AlignedAlloc*>(&::operator new[]))(8, std::align_val_t{64}); },
         [] { ::operator delete[](p, std::align_val_t{64}), p = nullptr; }},
        {"nothrow operator new", RealtimeCall::OperatorNew, false, false,
         [] { p = opaque(static_cast<NothrowAlloc*>(&::operator new))(8, std::nothrow); },
         undo_new},
        {"nothrow operator new[]", RealtimeCall::OperatorNew, false, false,
         [] { p = opaque(static_cast<NothrowAlloc*>(&::operator new[]))(8, std::nothrow); },
         [] { ::operator delete[](p), p = nullptr; }},
        {"aligned nothrow operator new", RealtimeCall::OperatorNew, false, false,
         [] {
             p = opaque(static_cast<AlignedNothrowAlloc*>(&::operator new))(8, std::align_val_t{64},
                                                                            std::nothrow);
         },
         undo_aligned_new},
        {"a std::vector's push_back", RealtimeCall::OperatorNew, false, false,
         [] {
             std::vector<int> v;
             v.push_back(1);
         },
         [] {}},
        {"operator delete", RealtimeCall::OperatorDelete, false, false,
         [] { opaque(static_cast<void (*)(void*)>(&::operator delete))(::operator new(8)); },
         [] {}},
        {"sized operator delete", RealtimeCall::OperatorDelete, false, false,
         [] {
             opaque(static_cast<void (*)(void*, std::size_t)>(&::operator delete))(
                 ::operator new(8), 8);
         },
         [] {}},
        {"aligned operator delete", RealtimeCall::OperatorDelete, false, false,
         [] {
             opaque(static_cast<void (*)(void*, std::align_val_t)>(&::operator delete))(
                 ::operator new(8, a), a);
         },
         [] {}},
        {"pthread_mutex_lock and std::mutex::lock", RealtimeCall::MutexLock, false, false,
         [] {
             static std::mutex m;
             m.lock();
             m.unlock();
         },
         [] {}},
        {"pthread_mutex_trylock", RealtimeCall::MutexTrylock, false, false,
         [] {
             static std::mutex m;
             if (m.try_lock()) m.unlock();
         },
         [] {}},
        {"pthread_mutex_timedlock", RealtimeCall::MutexTimedlock, false, false,
         [] {
             static pthread_mutex_t m = PTHREAD_MUTEX_INITIALIZER;
             timespec t{};
             clock_gettime(CLOCK_REALTIME, &t);
             if (opaque(&::pthread_mutex_timedlock)(&m, &t) == 0) pthread_mutex_unlock(&m);
         },
         [] {}},
        {"pthread_mutex_unlock", RealtimeCall::MutexUnlock, false, false,
         [] {
             static std::mutex m;
             const std::lock_guard lock(m);
         },
         [] {}},
        {"pthread_rwlock_rdlock", RealtimeCall::RwlockRead, false, false,
         [] {
             static std::shared_mutex m;
             const std::shared_lock lock(m);
         },
         [] {}},
        {"pthread_rwlock_wrlock", RealtimeCall::RwlockWrite, false, false,
         [] {
             static std::shared_mutex m;
             const std::unique_lock lock(m);
         },
         [] {}},
        {"pthread_rwlock_unlock", RealtimeCall::RwlockUnlock, false, false,
         [] {
             static std::shared_mutex m;
             const std::unique_lock lock(m);
         },
         [] {}},
        {"pthread_cond_timedwait", RealtimeCall::CondTimedwait, false, false,
         [] {
             static pthread_mutex_t m = PTHREAD_MUTEX_INITIALIZER;
             static pthread_cond_t c = PTHREAD_COND_INITIALIZER;
             timespec past{};  // long gone: returns at once
             pthread_mutex_lock(&m);
             opaque (&::pthread_cond_timedwait)(&c, &m, &past);
             pthread_mutex_unlock(&m);
         },
         [] {}},
        {"std::condition_variable::wait_for", RealtimeCall::CondTimedwait, false, false,
         [] {
             static std::mutex m;
             static std::condition_variable c;
             std::unique_lock lock(m);
             c.wait_for(lock, 1ns);
         },
         [] {}},
        {"pthread_cond_wait", RealtimeCall::CondWait, false, false,
         [] {
             static std::mutex m;
             static std::condition_variable c;
             bool waiting = false, woken = false;
             std::unique_lock lock(m);
             waiting = true;
             // It gets the mutex only once the marked thread waits (which releases it).
             std::thread waker([&] {
                 for (;;) {
                     const std::lock_guard held(m);
                     if (waiting) {
                         woken = true;
                         c.notify_one();
                         return;
                     }
                 }
             });
             c.wait(lock, [&] { return woken; });
             waker.join();
         },
         [] {}},
        {"pthread_cond_signal", RealtimeCall::CondSignal, false, false,
         [] {
             static std::condition_variable c;
             c.notify_one();
         },
         [] {}},
        {"pthread_cond_broadcast", RealtimeCall::CondBroadcast, false, false,
         [] {
             static std::condition_variable c;
             c.notify_all();
         },
         [] {}},
        {"open", RealtimeCall::Open, false, false, [] { fd = ::open("/dev/null", O_RDWR); },
         [] { ::close(fd); }},
        {"write", RealtimeCall::Write, false, false,
         [] { (void)opaque (&::write)(fd = ::open("/dev/null", O_RDWR), "x", 1); },
         [] { ::close(fd); }},
        {"read", RealtimeCall::Read, false, false,
         [] { (void)opaque (&::read)(fd = ::open("/dev/null", O_RDONLY), buffer, sizeof buffer); },
         [] { ::close(fd); }},
        {"close", RealtimeCall::Close, false, false,
         [] { opaque (&::close)(::open("/dev/null", O_RDONLY)); }, [] {}},
        {"fopen", RealtimeCall::Fopen, false, false, [] { file = std::fopen("/dev/null", "w"); },
         [] { std::fclose(file); }},
        {"fwrite", RealtimeCall::Fwrite, false, false,
         [] { opaque (&std::fwrite)("x", 1, 1, file = std::fopen("/dev/null", "w")); },
         [] { std::fclose(file); }},
        {"fprintf", RealtimeCall::Fwrite, false, false,
         [] { std::fprintf(file = std::fopen("/dev/null", "w"), "%d", 1); },
         [] { std::fclose(file); }},
        {"fclose", RealtimeCall::Fclose, false, false,
         [] { opaque (&std::fclose)(std::fopen("/dev/null", "r")); }, [] {}},
        {"fread", RealtimeCall::Fread, false, false,
         [] { (void)opaque (&std::fread)(buffer, 1, 1, file = std::fopen("/dev/zero", "r")); },
         [] { std::fclose(file); }},
    };
}

// Each kind of call, made on a marked thread, is counted; made on an unmarked one, it is not.
TEST(RealtimeSafety, EveryForbiddenCallIsSeenOnAMarkedThreadOnly) {
    if (!test::locks_and_io_interposed())
        GTEST_SKIP() << "this sanitizer's runtime is linked into the executable: locks and I/O "
                        "cannot be interposed without hiding them from it";
    const bool by_name = test::c_allocator_interposed_by_name();
    std::set<RealtimeCall> proven;
    for (const ForbiddenCall& c : controls()) {
        RealtimeCall expected = c.by_name;
        if (c.c_allocator && !by_name)  // under a sanitizer: its allocator's hooks count them
            expected = c.frees ? RealtimeCall::SanitizerFree : RealtimeCall::SanitizerAllocation;
        proven.insert(expected);
        const RealtimeCalls unmarked = [&] {
            const RealtimeCalls before = realtime_calls();
            std::thread([&] {
                c.call();
                c.undo();
            }).join();
            return realtime_calls() - before;
        }();
        EXPECT_EQ(unmarked.total(), 0u)
            << c.what << " on an unmarked thread: " << unmarked.describe();
        const RealtimeCalls seen = counted_on_marked_thread(c.call, c.undo);
        EXPECT_GE(seen[expected], 1u)
            << c.what << " on a marked thread was not counted as " << test::name(expected)
            << " (counted: " << seen.describe() << ")";
    }
    // No kind of call is counted without a control showing that it can be seen.
    for (int i = 0; i < static_cast<int>(RealtimeCall::Count); ++i) {
        const auto kind = static_cast<RealtimeCall>(i);
        const bool sanitizer_kind =
            kind == RealtimeCall::SanitizerAllocation || kind == RealtimeCall::SanitizerFree;
        const bool c_allocator_kind = kind <= RealtimeCall::Free;
        if (by_name ? sanitizer_kind : c_allocator_kind) continue;  // not counted in this build
        EXPECT_TRUE(proven.count(kind)) << test::name(kind) << " has no control";
    }
}

// Simulation::step, its probes and output, and a parameter set by slot, on a marked thread.
TEST(RealtimeSafety, StepProbesAndOutputMakeNoForbiddenCall) {
    BowedStringOptions o;
    Model model = build_bowed_string(o);
    Control c;
    c.id = "c", c.target = {"friction", "mu_s"}, c.source = Control::Source::Envelope;
    c.envelope = {{0, 0.8}, {1, 0.9}}, c.minimum = 0.5, c.maximum = 1.0;
    model.controls.push_back(c);
    Simulation sim(compile(model));
    sim.enable_accounting(true);
    // Resolved off the real-time path.
    const auto mu_d = sim.model().resolve_parameter({"friction", "mu_d"});
    const auto mid_damping = sim.model().resolve_parameter({"k30", "damping"});
    const auto mid_mass = sim.model().resolve_parameter({"s20", "mass"});
    ASSERT_EQ(sim.model().levels[mid_damping.level].uniform.count(), 1);
    const UniformRuns& runs = sim.model().levels[mid_damping.level].uniform;
    int runs_after_splits[2] = {};
    double sink = 0;
    const RealtimeCalls calls = counted_on_marked_thread([&] {
        for (int i = 0; i < 48000; ++i) {
            sim.step();
            sink += sim.output();
            for (std::size_t p = 0; p < sim.probe_count(); ++p) sink += sim.probe(p);
        }
        sim.write_slot(mu_d, 0.25);
        // Each splits the string's run of alike MATs, the loop then walks the runs, and they are
        // found afresh.
        sim.write_slot(mid_damping, 2.0 * sim.read_slot(mid_damping));
        runs_after_splits[0] = runs.count();
        sim.write_slot(mid_mass, 2.0 * sim.read_slot(mid_mass));
        runs_after_splits[1] = runs.count();
        for (int i = 0; i < 480; ++i) sim.step(), sink += sim.output();
        sim.refresh_uniform_runs();
        for (int i = 0; i < 480; ++i) sim.step(), sink += sim.output();
    });
    EXPECT_EQ(runs_after_splits[0], 2);
    EXPECT_EQ(runs_after_splits[1], 3);
    EXPECT_EQ(runs.count(), 3);
    EXPECT_EQ(calls.total(), 0u) << calls.describe();
    EXPECT_TRUE(std::isfinite(sink));
}

// A string in modal form: its points of a term per mode sum their modes (modal_kernel.cpp) and
// take the bow's and the bridges' forces at every step, its shape is read as the engine draws
// it (the points the step leaves out summed then), a mode's mass set while it plays moves
// its points' responses, and the engine's swap to a recompiled model (continue_from) reads the
// points afresh from their modes, on a marked thread.
TEST(RealtimeSafety, AModalStringStepsWithoutAForbiddenCall) {
    BowedStringOptions o;
    o.structure = Structure::Modal;
    o.masses = 40;
    const Model model = build_bowed_string(o);
    const CompiledModel compiled = compile(model);
    Simulation sim(compiled), swapped_in(compiled);
    std::vector<MatSlot> shape;  // as the engine draws it: most are points the step leaves out
    for (const std::string& id : string_points(model)) shape.push_back(compiled.mat_slots.at(id));
    ASSERT_GT(compiled.levels[0].derived_points.size(), 30u);
    std::vector<double> scratch(sim.state_size());
    const auto mode_mass = sim.model().resolve_parameter({"mode3", "mass"});
    std::size_t longest_point = 0;
    for (const auto& lv : sim.model().levels)
        for (const auto& p : lv.modal_points)
            longest_point = std::max(longest_point, p.modes.size());
    ASSERT_GT(longest_point, kModalSumLanes) << "its points are summed by the run kernels";
    double sink = 0, loudest = 0;
    const RealtimeCalls calls = counted_on_marked_thread([&] {
        for (int i = 0; i < 24000; ++i) {
            sim.step();
            sink += sim.output(), loudest = std::max(loudest, std::abs(sim.output()));
            if (i % 960 == 0)
                for (MatSlot s : shape) sink += sim.position(s);
        }
        sim.write_slot(mode_mass, 1.01 * sim.read_slot(mode_mass));
        for (int i = 0; i < 480; ++i) sim.step(), sink += sim.output();
        swapped_in.continue_from(sim, scratch);
        for (int i = 0; i < 480; ++i) swapped_in.step(), sink += swapped_in.output();
    });
    EXPECT_EQ(calls.total(), 0u) << calls.describe();
    EXPECT_TRUE(std::isfinite(sink));
    EXPECT_GT(loudest, 1e-3) << "it was bowed";
}

// The engine's real-time thread, run in this process through its real code path: run_engine on
// a null sink (whose thread calls RealtimeThread::render once a block, as a sound card's
// would), driven through the shared segment as the studio drives it. A whole session: play, bow a
// simulated hand (the haptic loop), glide parameters (the smoother), record takes (one stopped, one
// ended by a model swap), swap models with a cross-fade, mute a blow-up and swap in the reset
// model.
class EngineSession {
  public:
    explicit EngineSession(const std::string& haptic) : link_(link_options()) {
        EngineOptions o;
        o.segment = link_.segment_name();
        o.haptic = haptic;
        o.lock_memory = false;  // the engine's own process would; not the test's
        o.takes = std::filesystem::temp_directory_path().string();  // the takes' temp folders
        engine_ = std::thread([this, o] { exit_status_ = run_engine(o); });
    }
    ~EngineSession() { quit(); }

    int quit() {
        if (engine_.joinable()) {
            link_.quit();
            engine_.join();
        }
        return exit_status_;
    }

    link::EngineLink& link() { return link_; }

    // Reads everything the engine published, says the studio is alive, and tells whether `done`.
    bool pump(const std::function<bool()>& done = [] { return false; }) {
        link_.heartbeat();
        ipc::StatusFrame s;
        while (status_.try_pop(s)) {
            const auto kind = static_cast<ipc::StatusKind>(s.kind);
            if (kind == ipc::StatusKind::Error) errors_.push_back(s.text);
            if (kind == ipc::StatusKind::ModelLoaded) loaded_.push_back(s.sequence);
            if (kind == ipc::StatusKind::Take) takes_.push_back(s.text);
            if (kind == ipc::StatusKind::Blowup) ++blowups_;
            blocks_ = s.blocks;
        }
        ipc::ProbeFrame f;
        while (probes_.try_pop(f)) {
            ++frames_;
            normal_ = f.values[4], friction_ = std::max(friction_, std::abs(f.values[5]));
            hand_force_ = std::max(hand_force_, std::abs(f.values[7]));
        }
        return done();
    }

    // Bows on (the pad moving at 0.1 m/s, pressed) until `done`, waiting up to a generous
    // minute: the machine's speed decides how long it takes, never whether it happens.
    bool bow_until(const std::function<bool()>& done, double press = 0.0015) {
        return test::wait_for(
            [&] {
                slide_ += 0.0002;
                link_.gesture(slide_, press);
                return pump(done);
            },
            60000ms);
    }
    // Bows on for `count` more probe frames (samples played).
    bool bow_for(std::uint64_t count) {
        const std::uint64_t until = frames_ + count;
        return bow_until([&] { return frames_ >= until; });
    }
    bool loaded(std::uint32_t sequence) const {
        return std::find(loaded_.begin(), loaded_.end(), sequence) != loaded_.end();
    }
    bool take_said(const std::string& start) const {
        for (const auto& t : takes_)
            if (t.rfind(start, 0) == 0) return true;
        return false;
    }
    std::string said() const {
        std::string s;
        for (const auto& e : errors_) s += "error: " + e + "; ";
        for (const auto& t : takes_) s += "take: " + t + "; ";
        return s;
    }

    std::vector<std::string> errors_, takes_;
    std::vector<std::uint32_t> loaded_;
    std::uint64_t frames_ = 0, blocks_ = 0, blowups_ = 0;
    double normal_ = 0, friction_ = 0, hand_force_ = 0, slide_ = 0;

  private:
    static link::EngineLinkOptions link_options() {
        link::EngineLinkOptions o;
        o.archet_binary = ARCHET_BINARY;  // not started: the engine runs in this process
        return o;
    }

    link::EngineLink link_;
    ipc::SpscRing<ipc::StatusFrame> status_ = link_.status();
    ipc::SpscRing<ipc::ProbeFrame> probes_ = link_.probes();
    std::thread engine_;
    int exit_status_ = -1;
};

TEST(RealtimeSafety, TheEnginesRealtimeThreadMakesNoForbiddenCallInAWholeSession) {
    const RealtimeCalls before = realtime_calls();
    const std::uint64_t sleeps_before = test::realtime_sleeps();
    const auto dir = test::temp_dir("realtime-safety");
    const std::string string_220 = test::resource("models/bowed-string-220.json").string();
    const std::string harmonic = test::resource("models/bowed-string-220-harmonic.json").string();
    {
        EngineSession e("sim");  // the pad moves a simulated hand: the haptic loop runs
        auto& link = e.link();
        ASSERT_TRUE(test::wait_for(
            [&] {
                e.pump();
                return link.header().engine_state.load() ==
                       static_cast<std::uint32_t>(ipc::EngineState::Ready);
            },
            60000ms));
        const auto first = link.load_model(string_220);
        ASSERT_TRUE(
            test::wait_for([&] { return e.pump([&] { return e.loaded(first); }); }, 60000ms))
            << e.said();
        link.play();
        // The haptic loop: the pad moves the simulated hand, which bows the string and feels it.
        ASSERT_TRUE(e.bow_until([&] { return e.friction_ > 0.01 && e.hand_force_ > 0.01; }))
            << "the simulated hand bowed the string and felt it";

        // The smoother: the press axis inverted glides the bow off the string, and back.
        link.send_parameter({"hand_press", "position_scale"}, -1.0);
        ASSERT_TRUE(e.bow_until([&] { return e.normal_ == 0.0; })) << e.said();
        link.send_parameter({"hand_press", "position_scale"}, 1.0);
        ASSERT_TRUE(e.bow_until([&] { return e.normal_ > 0.01; })) << e.said();

        // A take, begun at a block boundary, fed samples, gestures and a parameter change, stopped.
        link.start_take((dir / "take-1").string());
        ASSERT_TRUE(e.bow_until([&] { return e.take_said("recording"); })) << e.said();
        ASSERT_TRUE(e.bow_for(4800));
        link.send_parameter({"friction", "mu_d"}, 0.3);
        ASSERT_TRUE(e.bow_for(4800));
        link.stop_take();
        ASSERT_TRUE(e.bow_until([&] {
            return e.take_said("written " + (dir / "take-1").string());
        })) << e.said();

        // A model swap while playing and recording: cross-faded, and the swap ends the take.
        link.start_take((dir / "take-2").string());
        ASSERT_TRUE(e.bow_for(4800));
        const auto swap = link.load_model(harmonic);
        ASSERT_TRUE(e.bow_until([&] { return e.loaded(swap); })) << e.said();
        ASSERT_TRUE(e.bow_for(4800)) << "the 10 ms cross-fade is over";
        ASSERT_TRUE(e.bow_until([&] {
            return e.take_said("written " + (dir / "take-2").string());
        })) << e.said();

        link.stop();
        EXPECT_EQ(e.quit(), 0);
        EXPECT_TRUE(e.errors_.empty()) << e.said();
    }
    {
        // A blow-up (the pad, with no device between, shoves the bow 60 m into the string):
        // muted within the block, and the reset model swapped in and played.
        EngineSession e("none");
        auto& link = e.link();
        const auto first = link.load_model(string_220);
        ASSERT_TRUE(
            test::wait_for([&] { return e.pump([&] { return e.loaded(first); }); }, 60000ms))
            << e.said();
        link.play();
        ASSERT_TRUE(e.bow_for(4800));
        const std::size_t loads = e.loaded_.size();
        ASSERT_TRUE(e.bow_until([&] { return e.blowups_ > 0; }, 60.0)) << e.said();
        link.gesture(0.0, 0.0);  // let go
        ASSERT_TRUE(test::wait_for([&] { return e.pump([&] { return e.loaded_.size() > loads; }); },
                                   60000ms))
            << e.said();
        const std::uint64_t until = e.frames_ + 4800;
        ASSERT_TRUE(
            test::wait_for([&] { return e.pump([&] { return e.frames_ >= until; }); }, 60000ms))
            << "the reset model plays";
        EXPECT_EQ(e.quit(), 0);
    }
    const RealtimeCalls during = realtime_calls() - before;
    EXPECT_GT(test::realtime_sleeps(), sleeps_before)
        << "the engine's real-time thread was marked, and its calls seen";
    EXPECT_EQ(during.total(), 0u) << "the engine's real-time thread called: " << during.describe();
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace archet
