// Attacks: the protocol (a press, then a slide at constant acceleration), one attack played
// and judged, and a grid of them on every core. The grid's text forms are in attack_file.cpp.

#include "archet/analysis/attack.hpp"

#include <cmath>

#include "archet/analysis/bow_probes.hpp"
#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/playability.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/common/grid_sweep.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/number_text.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/run_ticks.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

namespace {

constexpr int kSettle = 10;         // periods of steady motion that make it steady
constexpr double kTolerance = 0.1;  // of the period, for a period to count as steady
constexpr double kHeardFor = 0.6;   // s of sliding that an attack played to be heard lasts

double string_pitch(const Model& model) {
    const double f1 = string_first_mode(model).frequency;
    if (!(f1 > 0)) throw InputError(model.name, "has no string mode to count periods of");
    return f1;
}

// Model metres per device metre on the slide axis.
double slide_scale(const Model& model) {
    for (const auto& m : model.mats)
        if (m.kind == MatKind::Gesture && m.axis == GestureAxis::Slide && m.position_scale != 0)
            return m.position_scale;
    throw InputError(model.name, "has no hand on the slide axis (a gesture point with axis slide)");
}

// The latest time a transient may need: the first slip as late as allowed, then every
// period allowed and the steady ones, each as long as a steady period may be.
double longest_stroke(int periods_max, double period) {
    return kBowStart + kNoSlipWait + (periods_max + kSettle + 2) * (1 + kTolerance) * period;
}

// When a transient whose first slip came at `first` can no longer settle in time.
double unsettled_after(double first, double period, int periods_max, int settle = kSettle,
                       double tolerance = kTolerance) {
    return first + periods_max * period + (settle + 1) * (1 + tolerance) * period;
}

}  // namespace

const char* to_string(Transient transient) {
    switch (transient) {
        case Transient::None:
            return "none";
        case Transient::MultipleSlip:
            return "multiple_slip";
        case Transient::Prolonged:
            return "prolonged";
        case Transient::Sliding:
            return "sliding";
        case Transient::Stuck:
            return "stuck";
    }
    return "?";
}

Transient transient_from_string(const std::string& name) {
    for (Transient t :
         {Transient::None, Transient::MultipleSlip, Transient::Prolonged, Transient::Sliding})
        if (name == to_string(t)) return t;
    throw InputError(name, "is not a transient (none, multiple_slip, prolonged, sliding)");
}

const char* to_string(AttackKind kind) {
    switch (kind) {
        case AttackKind::Perfect:
            return "perfect";
        case AttackKind::MultipleSlip:
            return "multiple_slip";
        case AttackKind::Prolonged:
            return "prolonged";
        case AttackKind::Never:
            return "never";
    }
    return "?";
}

AttackKind attack_kind_from_string(const std::string& name) {
    for (AttackKind k :
         {AttackKind::Perfect, AttackKind::MultipleSlip, AttackKind::Prolonged, AttackKind::Never})
        if (name == to_string(k)) return k;
    throw InputError(name, "is not an attack (perfect, multiple_slip, prolonged, never)");
}

AttackTransient judge_transient(const std::vector<Slip>& slips, double period, double now,
                                int periods_max, int settle, double tolerance) {
    AttackTransient t;
    t.periods = periods_max;
    if (slips.empty()) return t;       // no slip yet: the caller's wait decides
    t.transient = Transient::Sliding;  // unless a period of it says otherwise
    const double first = slips.front().onset, latest_start = first + periods_max * period;
    auto interval = [&](std::size_t i) { return slips[i + 1].onset - slips[i].onset; };
    auto slid = [&](std::size_t i) { return slips[i].slid_through(slips[i + 1].onset); };
    auto steady = [&](std::size_t i) {
        return std::abs(interval(i) - period) <= tolerance * period && !slid(i);
    };
    // The transient is named by its first period that is not steady.
    for (std::size_t i = 0; i + 1 < slips.size() && slips[i].onset <= latest_start; ++i) {
        if (steady(i)) continue;
        // A second slip within the period; else a slip through most of it; else too long.
        t.transient = interval(i) < (1 - tolerance) * period ? Transient::MultipleSlip
                      : slid(i)                              ? Transient::Sliding
                                                             : Transient::Prolonged;
        break;
    }
    for (std::size_t k = 0; k < slips.size() && slips[k].onset <= latest_start; ++k) {
        std::size_t j = k;
        while (j < k + settle && j + 1 < slips.size() && steady(j)) ++j;
        if (j < k + settle) continue;
        t.decided = true;
        t.slips = static_cast<int>(k);
        t.periods = (slips[k].onset - first) / period;
        if (k == 0) t.transient = Transient::None;
        t.kind = k == 0 ? AttackKind::Perfect
                        : (t.transient == Transient::Prolonged ? AttackKind::Prolonged
                                                               : AttackKind::MultipleSlip);
        return t;
    }
    for (const Slip& slip : slips) t.slips += slip.onset <= latest_start;
    t.decided = now > unsettled_after(first, period, periods_max, settle, tolerance);
    return t;
}

Gesture attack_gesture(double press, double acceleration, double step, double duration) {
    std::vector<GestureKeyframe> k;
    k.push_back({0.0, 0.0, 0.0});
    k.push_back({kPressRamp, 0.0, press});
    for (int i = 0;; ++i) {
        const double t = kBowStart + i * step;
        if (t > duration) break;
        const double u = t - kBowStart;
        k.push_back({t, 0.5 * acceleration * u * u, press});
    }
    return Gesture("attack", std::move(k));
}

AttackPoint play_attack_point(const Model& model, const AttackGrid& grid, std::size_t index,
                              double pitch, std::vector<double>* sound) {
    AttackPoint p;
    p.index = index;
    p.acceleration = grid.acceleration(index);
    p.force = grid.force(index);
    Model variant = model;
    if (grid.position > 0) set_variant_parameter(variant, "bow.position", grid.position);
    validate_model(variant);
    if (!read_bow_only(variant, {ProbeKind::SlipVelocity}))
        throw InputError(model.name, "has no bow to play an attack with");
    if (!(pitch > 0)) pitch = string_pitch(variant);
    const double period = 1.0 / pitch;
    CompiledModel compiled = compile(variant);
    const CompiledLevel* hand = hand_level(compiled);
    if (!hand) throw InputError(model.name, "has no hand to bow it with (gesture points)");
    const Gesture stroke = attack_gesture(p.force / force_for_press(variant, 1.0),
                                          p.acceleration / slide_scale(variant), hand->dt,
                                          longest_stroke(grid.periods_max, period));
    Simulation sim(std::move(compiled));
    sim.set_gesture_track(&stroke);
    const DenormalGuard no_denormals;
    const double fs = sim.sample_rate();
    const auto start = static_cast<std::size_t>(std::lround(kBowStart * fs));
    const auto end = static_cast<std::size_t>(stroke.duration() * fs);
    SlipDetector detector(fs);
    std::vector<Slip> slips;
    double give_up = kNoSlipWait;  // s after the bow's start
    bool judged = false;
    // An attack to be heard plays on for a while after it is judged.
    const std::size_t heard = sound ? static_cast<std::size_t>((kBowStart + kHeardFor) * fs) : 0;
    if (sound) sound->clear();
    run_ticks(sim, end, [&](std::size_t i, double sample, const double* row) {
        if (judged && i >= heard) return false;
        if (sound) sound->push_back(sample);
        if (i < start || judged) return true;  // the bow has not moved yet, or it is over
        const double now = static_cast<double>(i + 1) / fs - kBowStart;
        const double slip = row[0];
        if (!std::isfinite(slip))
            throw InputError(model.name, "stopped being finite bowed at " +
                                             format_number(p.acceleration) + " m/s² and " +
                                             format_number(p.force) + " N");
        const bool starts = detector.add(i, slip);
        if (detector.ended() && !slips.empty()) slips.back().end = detector.end() - kBowStart;
        if (starts) {
            slips.push_back({detector.onset() - kBowStart});
            if (slips.size() == 1)
                give_up = unsettled_after(slips.front().onset, period, grid.periods_max);
            judged =
                judge_transient(slips, period, now, grid.periods_max, kSettle, kTolerance).decided;
        }
        judged = judged || now > give_up;
        return true;
    });
    if (!slips.empty()) p.first_slip = slips.front().onset;
    p.transient =
        judge_transient(slips, period, give_up + 1, grid.periods_max, kSettle, kTolerance);
    p.transient.decided = true;  // the stroke is over: what has not settled never did
    return p;
}

AttackMap play_attack(const Model& model, const AttackGrid& grid, int jobs, int shard, int shards,
                      const std::function<void(std::size_t, std::size_t)>& progress,
                      const std::atomic<bool>* cancel) {
    if (const std::string problem = grid.problem(); !problem.empty())
        throw InputError(model.name, "cannot play this grid: " + problem);
    shard_points(grid.size(), shard, shards);  // a bad shard is refused before anything runs
    // Everything a point needs is checked before the threads start.
    Model checked = model;
    if (grid.position > 0) set_variant_parameter(checked, "bow.position", grid.position);
    validate_model(checked);
    const double pitch = string_pitch(checked);
    force_for_press(checked, 1.0);
    slide_scale(checked);
    AttackMap map{grid, {}, pitch};
    map.points = sweep_grid<AttackPoint>(
        model.name, grid.size(), jobs, shard, shards,
        [&](std::size_t index) { return play_attack_point(model, grid, index, pitch); }, progress,
        cancel);
    return map;
}

}  // namespace archet
