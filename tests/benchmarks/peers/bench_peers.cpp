// Archet against its peers on a 60-mass bowed string at 220 Hz, timed interleaved in one run:
// each round renders a quarter second on every contender in turn, and the medians over the
// rounds are compared, so that a slower moment of the machine falls on all of them alike.
//   archet paper    the paper's chaplet: link damping alone, bridges, a point bow
//                   (`archet new bowed-string --pitch 220 --masses 60 --paper`); all three
//                   run in Simulation::run(), the bowed chain's loop, in the build of it that
//                   fastest_chain_build() finds fastest here, as the engine and `render` do
//   archet bare     the shipped string without its body: losses to its rest points too, and a
//                   bow spread over three masses
//   archet + body   the shipped string (`archet new bowed-string --pitch 220 --masses 60`)
//   mi.lib paper,   the first two in Faust's mi.lib, written by mi_string_writer and compiled
//   mi.lib bare     by faust, with mi.lib's own bow (a friction curve, no normal force)
//   stk Bowed       STK's bowed-string waveguide (Smith), the classic cheap bowed string
//   floor           the paper string's step written out by hand for that one model, its string
//                   in AVX-512 registers (floor_string.hpp): the same bytes as archet paper
//                   (checked first), so what this scheme costs here whatever the engine
//   floor fused     the same with the chain's multiply-adds fused (FMA), a change of the
//                   scheme's arithmetic: its largest difference is printed
// A peer that is not installed is skipped with a message (Debian: faust, libstk-dev).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "archet/common/denormal_guard.hpp"
#include "archet/model/gesture.hpp"
#include "archet/physics/chain_build_choice.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "floor_string.hpp"
#include "peer_string.hpp"

#if ARCHET_PEER_FAUST
#include "mi_bare_string.hpp"
#include "mi_paper_string.hpp"
#endif
#if ARCHET_PEER_STK
#include <stk/Bowed.h>
#endif

namespace {

using archet::peers::PeerString;

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

// Bowed at 0.1 m/s from the gesture points, as `archet bench` bows.
class ArchetString {
  public:
    explicit ArchetString(PeerString string)
        : stroke_(archet::steady_bow_gesture(archet::peers::kBowSpeed, 0.0015, 1e4)),
          sim_(archet::compile(archet::build_bowed_string(archet::peers::string_options(string)),
                               kSampleRate)) {
        sim_.set_gesture_track(&stroke_);
        // The build of the chain loop the engine, `render` and `play` would run it in here.
        sim_.set_chain_build(archet::fastest_chain_build(sim_));
    }
    void render(double* out, int count) { sim_.run({out, static_cast<std::size_t>(count)}); }
    archet::ChainBuild chain_build() const { return sim_.chain_build(); }

  private:
    archet::Gesture stroke_;
    archet::Simulation sim_;
};

// The floor of the paper string (floor_string.hpp), bowed as ArchetString bows it.
template <bool kFused>
class FloorContender {
  public:
    FloorContender()
        : stroke_(archet::steady_bow_gesture(archet::peers::kBowSpeed, 0.0015, 1e4)),
          sim_(paper_string()) {
        sim_.set_gesture_track(&stroke_);
        error_ = archet::peers::layout_error(sim_);
        if (error_.empty()) floor_.emplace(sim_, &stroke_);
    }
    const std::string& error() const { return error_; }
    void render(double* out, int count) { floor_->render(out, count); }
    /// The floor's sound against the scheme's over the first `samples`.
    struct Difference {
        int samples_differing = 0;  ///< in their bytes (a NaN or a −0 against +0 too)
        double largest = 0;         ///< |floor − scheme| where they differ
        double scheme_peak = 0;     ///< the scheme's largest |sample|: 0 would prove nothing
    };
    Difference difference(int samples) {
        FloorContender fresh;
        std::vector<double> floor(samples);
        for (int done = 0; done < samples; done += kBlock)
            fresh.render(floor.data() + done, std::min(kBlock, samples - done));
        Difference d;
        for (int i = 0; i < samples; ++i) {
            fresh.sim_.step();
            const double scheme = fresh.sim_.output();
            d.scheme_peak = std::max(d.scheme_peak, std::abs(scheme));
            if (std::memcmp(&scheme, &floor[i], sizeof scheme) == 0) continue;
            ++d.samples_differing;
            const double apart = std::abs(floor[i] - scheme);
            d.largest = std::isnan(apart) ? HUGE_VAL : std::max(d.largest, apart);
        }
        return d;
    }

  private:
    static archet::Simulation paper_string() {
        return archet::Simulation(archet::compile(
            archet::build_bowed_string(archet::peers::string_options(PeerString::Paper)),
            kSampleRate));
    }
    archet::Gesture stroke_;
    archet::Simulation sim_;
    std::string error_;
    std::optional<archet::peers::FloorString<kFused>> floor_;
};

// Adds the floor if it stands for the paper string here and plays its sound; says why not.
template <bool kFused>
void add_floor(const std::string& name,
               const std::function<void(std::string, std::function<void(double*, int)>)>& add) {
    auto floor = std::make_shared<FloorContender<kFused>>();
    if (!floor->error().empty()) {
        std::printf("%s: skipped (%s)\n", name.c_str(), floor->error().c_str());
        return;
    }
    const int samples = static_cast<int>(kSampleRate);  // a second: the bow lands and plays
    const auto d = floor->difference(samples);
    if (!(d.scheme_peak > 0.0)) {
        std::printf("%s: skipped (the scheme is silent over its first second)\n", name.c_str());
        return;
    }
    if (!kFused && d.samples_differing != 0) {
        std::printf(
            "%s: skipped (%d of %d samples are not the scheme's bytes, off by up to %.3g "
            "of %.3g)\n",
            name.c_str(), d.samples_differing, samples, d.largest, d.scheme_peak);
        return;
    }
    if (kFused)
        std::printf("%s: its sound differs from the scheme's by at most %.3g of %.3g (%.2g)\n",
                    name.c_str(), d.largest, d.scheme_peak, d.largest / d.scheme_peak);
    else
        std::printf("%s: the same bytes as the scheme over %d samples\n", name.c_str(), samples);
    add(name, [floor](double* out, int count) { floor->render(out, count); });
}

#if ARCHET_PEER_FAUST
// A mi.lib string reads the bow's position as its input: a stroke at constant speed.
template <class Dsp>
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
    Dsp dsp_;
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

template <class Instrument>
std::function<void(double*, int)> renderer(std::shared_ptr<Instrument> instrument) {
    return [instrument](double* out, int count) { instrument->render(out, count); };
}

}  // namespace

int main() {
    const archet::DenormalGuard no_denormals;
    std::vector<Contender> contenders;
    auto add = [&](std::string name, std::function<void(double*, int)> render) {
        contenders.push_back({std::move(name), std::move(render), {}, 0.0, 0, true});
    };
    const auto paper = std::make_shared<ArchetString>(PeerString::Paper);
    const auto bare = std::make_shared<ArchetString>(PeerString::Bare);
    const auto body = std::make_shared<ArchetString>(PeerString::Body);
    add("archet paper", renderer(paper));
    add("archet bare", renderer(bare));
    add("archet + body", renderer(body));
    add_floor<false>("floor", add);
    add_floor<true>("floor fused", add);
#if ARCHET_PEER_FAUST
    add("mi.lib paper", renderer(std::make_shared<MiLibString<MiPaperString>>()));
    add("mi.lib bare", renderer(std::make_shared<MiLibString<MiBareString>>()));
#else
    std::printf(
        "faust mi.lib: skipped (faust was not found when this was configured: "
        "apt install faust)\n");
#endif
#if ARCHET_PEER_STK
    stk::Stk::setSampleRate(kSampleRate);
    auto bowed = std::make_shared<stk::Bowed>();
    bowed->noteOn(archet::peers::kPitch, 0.8);
    add("stk Bowed", [bowed](double* out, int count) {
        for (int i = 0; i < count; ++i) out[i] = bowed->tick();
    });
#else
    std::printf(
        "stk Bowed: skipped (STK was not found when this was configured: "
        "apt install libstk-dev)\n");
#endif
    // Warm up (past the bow's landing), then the interleaved rounds.
    for (auto& c : contenders) {
        double block[kBlock];
        for (int done = 0; done < 14400; done += kBlock) c.render(block, kBlock);
    }
    for (int round = 0; round < kRounds; ++round)
        for (auto& c : contenders) time_round(c);

    std::printf(
        "%d interleaved rounds of %d samples at %.0f Hz, blocks of %d, one core; "
        "Archet's chain loop: %s for paper, %s bare, %s + body\n\n",
        kRounds, kRoundSamples, kSampleRate, kBlock, archet::chain_build_name(paper->chain_build()),
        archet::chain_build_name(bare->chain_build()),
        archet::chain_build_name(body->chain_build()));
    std::printf("%-16s %10s %10s %10s\n", "contender", "ns/sample", "best", "rms out");
    std::map<std::string, double> ns;
    for (const auto& c : contenders) {
        ns[c.name] = median(c.ns_per_sample);
        const double best = *std::min_element(c.ns_per_sample.begin(), c.ns_per_sample.end());
        std::printf("%-16s %10.1f %10.1f %10.3g%s\n", c.name.c_str(), ns[c.name], best,
                    std::sqrt(c.sum_squares / static_cast<double>(c.samples)),
                    c.finite ? "" : "  (not finite!)");
    }
    std::printf("\n");
    auto ratio = [&](const std::string& a, const std::string& b) {
        if (ns.count(a) && ns.count(b))
            std::printf("%-14s / %-14s %6.3f\n", a.c_str(), b.c_str(), ns[a] / ns[b]);
    };
    ratio("archet paper", "mi.lib paper");
    ratio("archet bare", "mi.lib bare");
    ratio("archet paper", "stk Bowed");
    ratio("floor", "mi.lib paper");
    ratio("floor fused", "mi.lib paper");
    ratio("floor", "stk Bowed");
    ratio("floor fused", "stk Bowed");
    ratio("archet paper", "floor");
    ratio("archet bare", "stk Bowed");
    return 0;
}
