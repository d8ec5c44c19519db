// Archet against its peers on one bowed string, timed interleaved in one run: each round
// renders a quarter second on every contender in turn, and the medians over the rounds are
// compared, so that a slower moment of the machine falls on all of them alike.
//   archet (bare)   the 60-mass string and its bridges, bowed by Archet's bow module
//   archet (body)   the shipped string: the same with its violin body (`archet new
//                   bowed-string --pitch 220 --masses 60`)
//   faust mi.lib    the bare string in mi.lib, written by mi_string_writer, compiled by faust
//   stk Bowed       STK's bowed-string waveguide (Smith), the classic cheap bowed string
// A peer that is not installed is skipped with a message (Debian: faust, libstk-dev).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "archet/common/denormal_guard.hpp"
#include "archet/model/gesture.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "peer_string.hpp"

#if ARCHET_PEER_FAUST
#include "mi_bowed_string.hpp"
#endif
#if ARCHET_PEER_STK
#include <stk/Bowed.h>
#endif

namespace {

constexpr double kSampleRate = 48000.0;
constexpr int kBlock = 64;            // samples per call, as an audio callback asks
constexpr int kRoundSamples = 12000;  // a quarter second
constexpr int kRounds = 15;

struct Contender {
    std::string name;
    std::function<void(double* out, int count)> render;  ///< the next `count` samples
    std::vector<double> ns_per_sample;
    double sum_squares = 0;
    std::size_t samples = 0;
    bool finite = true;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

class ArchetString {
  public:
    explicit ArchetString(bool with_body)
        : stroke_(archet::steady_bow_gesture(archet::peers::kBowSpeed, 0.0015, 1e4)),
          sim_(archet::compile(archet::build_bowed_string(archet::peers::string_options(with_body)),
                               kSampleRate)) {
        sim_.set_gesture_track(&stroke_);
    }
    void render(double* out, int count) {
        for (int i = 0; i < count; ++i) {
            sim_.step();
            out[i] = sim_.output();
        }
    }

  private:
    archet::Gesture stroke_;
    archet::Simulation sim_;
};

#if ARCHET_PEER_FAUST
// The mi.lib string reads the bow's position as its input: a stroke at constant speed.
class MiLibString {
  public:
    MiLibString() { dsp_.init(static_cast<int>(kSampleRate)); }
    void render(double* out, int count) {
        double position[kBlock];
        for (int i = 0; i < count; ++i)
            position[i] = archet::peers::kBowSpeed * static_cast<double>(tick_++) / kSampleRate;
        double* inputs[] = {position};
        double* outputs[] = {out};
        dsp_.compute(count, inputs, outputs);
    }

  private:
    MiBowedString dsp_;
    long tick_ = 0;
};
#endif

void time_round(Contender& c) {
    double block[kBlock];
    const auto start = std::chrono::steady_clock::now();
    for (int done = 0; done < kRoundSamples; done += kBlock) {
        c.render(block, kBlock);
        for (double v : block) {
            c.sum_squares += v * v;
            c.finite = c.finite && std::isfinite(v);
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    c.samples += kRoundSamples;
    c.ns_per_sample.push_back(seconds * 1e9 / kRoundSamples);
}

}  // namespace

int main() {
    const archet::DenormalGuard no_denormals;
    std::vector<Contender> contenders;
    auto add = [&](std::string name, std::function<void(double*, int)> render) {
        contenders.push_back({std::move(name), std::move(render), {}, 0.0, 0, true});
    };
    auto bare = std::make_shared<ArchetString>(false);
    auto body = std::make_shared<ArchetString>(true);
    add("archet, 60 masses (bare)", [bare](double* o, int n) { bare->render(o, n); });
    add("archet, 60 masses + violin body", [body](double* o, int n) { body->render(o, n); });
#if ARCHET_PEER_FAUST
    auto mi = std::make_shared<MiLibString>();
    add("faust mi.lib, 60 masses (bare)", [mi](double* o, int n) { mi->render(o, n); });
#else
    std::printf(
        "faust mi.lib: skipped (faust was not found when this was configured: apt install "
        "faust)\n");
#endif
#if ARCHET_PEER_STK
    stk::Stk::setSampleRate(kSampleRate);
    auto bowed = std::make_shared<stk::Bowed>();
    bowed->noteOn(archet::peers::kPitch, 0.8);
    add("stk Bowed (waveguide)", [bowed](double* o, int n) {
        for (int i = 0; i < n; ++i) o[i] = bowed->tick();
    });
#else
    std::printf(
        "stk Bowed: skipped (STK was not found when this was configured: apt install "
        "libstk-dev)\n");
#endif
    // Warm up (past the bow's landing), then the interleaved rounds.
    for (auto& c : contenders) {
        double block[kBlock];
        for (int done = 0; done < 14400; done += kBlock) c.render(block, kBlock);
    }
    for (int round = 0; round < kRounds; ++round)
        for (auto& c : contenders) time_round(c);

    const double reference = median(contenders.front().ns_per_sample);
    std::printf(
        "%d interleaved rounds of %d samples at %.0f Hz, blocks of %d, one core; "
        "Archet's chain loop: %s\n\n",
        kRounds, kRoundSamples, kSampleRate, kBlock,
        archet::chain_build_name(archet::chosen_chain_build()));
    std::printf("%-34s %12s %12s %14s %10s\n", "contender", "ns/sample", "best", "bare / this",
                "rms out");
    for (const auto& c : contenders) {
        const double ns = median(c.ns_per_sample);
        const double best = *std::min_element(c.ns_per_sample.begin(), c.ns_per_sample.end());
        std::printf("%-34s %12.1f %12.1f %14.3f %10.3g%s\n", c.name.c_str(), ns, best,
                    reference / ns, std::sqrt(c.sum_squares / static_cast<double>(c.samples)),
                    c.finite ? "" : "  (not finite!)");
    }
    return 0;
}
