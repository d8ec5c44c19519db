#include "loaded_model.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <vector>

#include "archet/common/denormal_guard.hpp"
#include "archet/common/input_error.hpp"
#include "archet/ipc/segment_layout.hpp"
#include "archet/model/string_points.hpp"
#include "archet/physics/chain_build_choice.hpp"

namespace archet {

namespace {

// A sanitizer's instrumented build runs the same code slower than the release build whose
// real-time behaviour the model-cost check judges: its measurements are scaled back, so that CI
// under a sanitizer accepts what a release engine plays and still refuses what it cannot. The
// factors stay under what `archet bench` measures on a 30,000-mass chain (AddressSanitizer
// 2.5-3 times, ThreadSanitizer about 24 times the release build's time).
#if defined(__SANITIZE_THREAD__)
constexpr double kInstrumentationSlowdown = 10;
#elif defined(__SANITIZE_ADDRESS__)
constexpr double kInstrumentationSlowdown = 2;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
constexpr double kInstrumentationSlowdown = 10;
#elif __has_feature(address_sanitizer)
constexpr double kInstrumentationSlowdown = 2;
#else
constexpr double kInstrumentationSlowdown = 1;
#endif
#else
constexpr double kInstrumentationSlowdown = 1;
#endif

// A chunk is one of the engine's runs at their longest with an energy probe (kEnergyProbeEvery).
constexpr int kCostSamples = 2048, kCostChunk = static_cast<int>(ipc::kEnergyProbeEvery);
constexpr double kCostSeconds = 0.02, kCostShare = 0.7;

}  // namespace

std::unique_ptr<LoadedModel> nrt_prepare_model(const Model& model, double sample_rate,
                                               const HapticChoice& haptic, std::uint32_t sequence,
                                               std::uint64_t generation,
                                               std::optional<ChainBuild> build) {
    auto loaded = std::make_unique<LoadedModel>();
    loaded->resolver = compile(model, sample_rate);  // the device's clock is the master
    loaded->simulation = std::make_unique<Simulation>(loaded->resolver);
    loaded->simulation->set_gesture_track(nullptr);  // live: the device or the pad plays it
    loaded->simulation->set_chain_build(build ? *build : fastest_chain_build(*loaded->simulation));
    if (haptic.device) loaded->haptic.emplace(*haptic.device, haptic.hand, *loaded->simulation);
    if (const CompiledLevel* hand = hand_level(loaded->resolver))
        loaded->haptic_divider = static_cast<std::uint64_t>(hand->divider),
        loaded->haptic_dt = hand->dt;
    const std::vector<std::string> points = string_points(model);
    for (std::size_t i : drawn_points(points.size(), ipc::kMaxShapePoints))
        loaded->shape.push_back(loaded->resolver.mat_slots.at(points[i]));
    loaded->shape_spread_over = static_cast<std::uint32_t>(points.size());
    for (std::size_t p = 0; p < loaded->resolver.probes.size(); ++p)
        if (loaded->resolver.probes[p].kind == ProbeKind::Energy) {
            loaded->has_energy_probe = true, loaded->energy_probe = p;
            break;
        }
    loaded->held_energy = loaded->simulation->stored_energy();  // until its first reading
    loaded->sequence = sequence;
    loaded->generation = generation;
    return loaded;
}

// A copy of the model is played for at most kCostSamples samples or kCostSeconds as the
// real-time thread plays it (a run of ticks reading every probe, then the stored energy for the
// scopes when the model has an energy probe): its fastest chunk's time per sample is what the
// model needs at least. Above kCostShare of the device's time per sample it cannot keep up and
// is refused.
void nrt_check_cost(const std::string& path, const LoadedModel& loaded, double sample_rate,
                    int block_frames) {
    const DenormalGuard no_denormals;
    Simulation copy(loaded.resolver);
    copy.set_gesture_track(nullptr);
    copy.set_chain_build(loaded.simulation->chain_build());
    std::vector<double> sound(kCostChunk), rows(kCostChunk * copy.probe_count());
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    double best = std::numeric_limits<double>::infinity();  // s per sample
    for (int done = 0; done < kCostSamples;) {
        const auto t0 = clock::now();
        const std::size_t n = copy.run(sound, {.values = rows.data(), .energy = false});
        if (loaded.has_energy_probe) (void)copy.stored_energy();
        const auto t1 = clock::now();
        done += static_cast<int>(n);
        best = std::min(best, std::chrono::duration<double>(t1 - t0).count() / n);
        if (n < sound.size() || std::chrono::duration<double>(t1 - start).count() > kCostSeconds)
            break;
    }
    const double needs = best / kInstrumentationSlowdown, budget = 1.0 / sample_rate;
    if (needs <= kCostShare * budget) return;
    const int block = block_frames;
    char said[ipc::kTextSize];
    std::snprintf(said, sizeof said,
                  "cannot play in real time: this model needs %.3g ms per block of %d "
                  "frames, which lasts %.3g ms at %g Hz (over %d %% of one core); reduce the "
                  "masses and links",
                  needs * block * 1e3, block, budget * block * 1e3, sample_rate,
                  static_cast<int>(kCostShare * 100));
    throw InputError(path, said);
}

}  // namespace archet
