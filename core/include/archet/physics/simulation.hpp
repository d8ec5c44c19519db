#pragma once
// Runs a compiled model: one step() per tick of the master clock, the same call for tests and
// the real-time engine, or run() over a block of ticks (offline rendering, benchmarks), which
// gives the same bytes. Neither allocates.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "archet/model/gesture.hpp"
#include "archet/physics/compiled_model.hpp"

namespace archet {

enum class ChainBuild;  ///< chain_kernel.hpp

class Simulation {
  public:
    explicit Simulation(CompiledModel model);
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;
    /// Moves keep the compiled arrays' storage, which the resolved hand links point into.
    Simulation(Simulation&&) = default;
    Simulation& operator=(Simulation&&) = default;

    /// Plays a gesture track: each gesture point reads it at its own ticks. The gesture
    /// must outlive the simulation's use of it.
    void set_gesture_track(const Gesture* gesture);
    /// Live device positions (used when no track is set).
    void set_device_position(GestureSample position) { device_ = position; }
    GestureSample device_position() const { return device_; }
    /// The force the device should render per axis: the mean force of the model on the gesture
    /// points of that axis over their last period, times their force_scale (N).
    GestureSample device_force() const;

    /// Advances one tick of the master clock.
    void step();
    /// Advances out.size() ticks and writes the output after each into `out`: the same bytes as
    /// step() then output() at every tick. A bowed chain (see bowed_chain_misfit()) runs a loop
    /// written for its shape, which asks once per call what the general step asks at every
    /// tick. Stops after a tick whose output is not finite; returns the ticks it ran.
    std::size_t run(std::span<double> out);
    /// run() with the bowed chain's loop in a given build (tests and benchmarks): it must run
    /// on this CPU (chain_build_runs_here()).
    std::size_t run(std::span<double> out, ChainBuild build);
    /// The build of the bowed chain's loop that run() takes from here on (at first the widest
    /// this CPU runs; fastest_chain_build() finds the fastest for the model): every build gives
    /// the same bytes. It must run on this CPU.
    void set_chain_build(ChainBuild build);
    ChainBuild chain_build() const { return chain_build_; }
    /// Where run() also writes the probes after each tick: out.size() rows of probe_count()
    /// values, row i what probe() reads after tick i. The stored energy is a sum over every
    /// element, nearly a step's cost: its probes' columns are written only with `energy`,
    /// and left as they were without it (the engine reads it every 16th tick and holds it).
    struct ProbeRows {
        double* values = nullptr;
        bool energy = true;
    };
    /// run() that also reads the probes after each tick: the same bytes as step(), output()
    /// and probe() at every tick, and for a bowed chain the same loop. Stops also after a tick
    /// whose probes read something not finite.
    std::size_t run(std::span<double> out, ProbeRows probes);
    /// Why run() steps this model with the general step, or "" when it runs it as a bowed chain:
    /// a chain of masses at audio rate, with or without grounds, a body and other modal points
    /// and links and fingers, with one bow held by at most four hand links from slower gesture
    /// points, no controls, no gesture points at audio rate, no links between rate levels but
    /// the hand's. Energy accounts (enable_accounting()) and chain rest lengths also take the
    /// general step (a length set back to 0 counts as none after refresh_uniform_runs()).
    std::string bowed_chain_misfit() const;

    /// Writes a parameter's compiled slot while running (controls, the smoother, the engine):
    /// no check, the value was validated against the model before it was resolved.
    void write_slot(const ParameterSlot& slot, double value);
    /// The slot's current value, in the model file's units.
    double read_slot(const ParameterSlot& slot) const;
    /// After a batch of writes (a knob that scales every damper, the end of a glide): finds
    /// again the runs of alike MATs whose coefficients the chain loop broadcasts, which each
    /// write could only split or shorten, and whether any chain link still has a rest length
    /// (one set back to 0 lets run() take the bowed chain's loop again). O(MATs), no allocation.
    void refresh_uniform_runs();

    /// The whole state of a running model (positions, link and bow states, parameters, the
    /// clock) as plain numbers: enough to resume it exactly, e.g. to re-render a take started
    /// mid-performance. save_state() does not allocate (real-time safe); `out` holds
    /// state_size() values.
    std::size_t state_size() const;
    void save_state(double* out) const;
    /// Resumes from a saved state of the same compiled model (same state_size()). Set the
    /// gesture track first: setting it moves the gesture points.
    void load_state(const double* in);
    /// Takes over the state of `from`, the same elements compiled with the bow's contact on
    /// other masses (the bow moved along the string): its motion, parameters and clock, the
    /// modal points read from this model's modes. `scratch` holds state_size() values, so it is
    /// real-time safe. False, and nothing changed, when the two states do not match.
    bool continue_from(const Simulation& from, std::span<double> scratch);

    /// Computes as scheme revision `revision` (1 … kSchemeRevision) did where this Archet still
    /// can, so that a take played under it re-renders to the byte: before revision 4 the friction
    /// solve divided by T and by the masses' response (common/scheme_revision.hpp). A
    /// simulation that continues from another computes as that one does.
    void compute_as_of(int revision);

    /// Keeps the per-element dissipation (slower; off by default).
    void enable_accounting(bool on);

    std::uint64_t tick() const { return tick_; }
    double time() const { return static_cast<double>(tick_) / model_.sample_rate; }
    double sample_rate() const { return model_.sample_rate; }

    /// The model's audio output after the last step.
    double output() const;
    /// Value of probe i after the last step (SI units).
    double probe(std::size_t i) const;
    std::size_t probe_count() const { return model_.probes.size(); }

    /// Where MAT s is after the last step, and its velocity over that step: a modal point the
    /// step leaves out (CompiledLevel::derived_points) summed from its modes.
    double position(MatSlot s) const;
    double velocity(MatSlot s) const;

    /// Stored energy in its discrete-consistent form (J): kinetic ½m((x[n]−x[n−1])/T)², plus
    /// ½K·d[n]·d[n−1] per spring, which the undamped scheme conserves exactly, minus
    /// (Z/4T)·(d[n]−d[n−1])² per damper, which makes every step's dissipation non-negative.
    double stored_energy() const;
    /// Total work done on the model by the gesture points since the start (J), exact in the
    /// scheme's energy after every step: stored energy minus hand work never rises.
    double hand_work() const;
    /// Power delivered by the hand over the last period of each gesture point (W).
    double power_in() const;
    /// Total energy dissipated per element since the start (J), indexed like Model::lias
    /// then Model::mats (oscillator grounds); needs accounting enabled.
    const std::vector<double>& dissipated_by_element() const { return dissipated_; }

    const CompiledModel& model() const { return model_; }
    CompiledModel& model() { return model_; }

  private:
    /// Calls `field` on every number of the state, in a fixed order (see simulation_state.cpp).
    template <class Self, class Field>
    static void for_each_state(Self& self, Field&& field);
    void apply_controls();
    void compute_link_forces(CompiledLevel& level);
    void compute_hand_link_forces();
    void compute_cross_link_forces();
    /// position() and velocity() of a MAT the step moves, as stored.
    double stored_position(MatSlot s) const { return model_.levels[s.level].x()[s.index]; }
    double stored_velocity(MatSlot s) const;
    /// Where a cross-rate link sees its end s: at its tick in this step, or at the next step's.
    double seen_position(MatSlot s, CompiledCrossLink::EndRate rate, bool between_steps) const;
    void integrate(CompiledLevel& level);
    void solve_bow(CompiledLevel& level, CompiledBow& bow);
    void solve_finger(CompiledLevel& level, CompiledFinger& finger);
    double response(const CompiledLevel& level, int storage) const;
    void push(CompiledLevel& level, int storage, double force);
    void push_pair(CompiledLevel& level, int a, double force_a, int b, double force_b);
    double finger_stored_energy(const CompiledLevel& level, const CompiledFinger& finger) const;
    double finger_dissipation(const CompiledLevel& level, const CompiledFinger& finger) const;
    void update_gesture_points(CompiledLevel& level);
    void update_modal_points(CompiledLevel& level);
    /// Each modal point's position now and a step ago, and its response, from its modes.
    void refresh_modal_points();
    /// Adds the motion a force on a modal point causes over this step, to its modes and so to
    /// every point of its body.
    void apply_modal_force(CompiledLevel& level, int point, double force);
    void account(CompiledLevel& level);
    /// The countdowns of the levels from `first` on, at the start of a tick (see step()):
    /// whether any of them ticks.
    bool count_down_levels(int first);
    std::string bowed_chain_shape_misfit() const;
    bool runs_as_bowed_chain() const {
        return bowed_chain_ && !accounting_ && !model_.levels[0].has_chain_lengths;
    }
    struct BowedChainFrame;  ///< what run_bowed_chain() holds over a block
    struct BowedChainLoop;   ///< its ticks, built per instruction set
    /// run() in that build, reading the probes into `probes` when it has values.
    std::size_t run_in(std::span<double> out, ChainBuild build, ProbeRows probes);
    std::size_t run_bowed_chain(std::span<double> out, ChainBuild build, ProbeRows probes);
    /// Row `tick` of `probes` (see ProbeRows), after that tick: whether all it read is finite.
    bool read_probe_row(ProbeRows probes, std::size_t tick) const;
    static constexpr int kMostHandLinks = 4;  ///< the bowed chain's loop holds them in its frame
    double gesture_axis(GestureAxis axis, double t) const;

    CompiledModel model_;
    const Gesture* track_ = nullptr;
    GestureSample device_{};
    std::uint64_t tick_ = 0;
    double hand_work_ = 0;
    bool accounting_ = false;
    bool friction_divides_ = false;  ///< as before scheme revision 4 (compute_as_of())
    /// The model's shape is a bowed chain's (run()), found once: its structure never changes.
    bool bowed_chain_ = false;
    ChainBuild chain_build_;  ///< run()'s (set_chain_build())
    std::vector<double> dissipated_;
    /// Per level: does it tick this step. (int, not char: a char store may alias anything.)
    std::vector<int> active_;
    std::vector<int> countdown_;       ///< per level: steps until its next tick
    std::vector<double> period_done_;  ///< per level: share of its period gone at this step
    struct HandLinkPlan {              ///< a hand link with its ends' addresses resolved
        CompiledCrossLink* link;
        CompiledLevel* hand_level;
        CompiledLevel* end_level;
        int hand_level_index, hand_index, end_index;
        double* end_force;   ///< the end's `external`
        double* hand_force;  ///< the hand point's `external`
        CompiledGesturePoint* gesture;
        double hand_weight;  ///< the link's share of the hand's period
    };
    std::vector<HandLinkPlan> hand_plan_;
};

// Inline: the bowed chain's loop counts down at every tick. Countdowns rather than tick % divider:
// a 64-bit division per level costs more than the whole step of a small model.
inline bool Simulation::count_down_levels(int first) {
    const int levels = static_cast<int>(model_.levels.size());
    const CompiledLevel* const level = model_.levels.data();
    bool any = false;
    for (int l = first; l < levels; ++l) {
        const bool ticks = countdown_[l] == 0;
        active_[l] = ticks;
        any |= ticks;
        countdown_[l] = ticks ? level[l].divider - 1 : countdown_[l] - 1;
        // How far into its period a faster link sees this level (see seen_position()).
        period_done_[l] =
            ticks ? 1.0 : (level[l].divider - 1 - countdown_[l]) * level[l].inverse_divider;
    }
    return any;
}

// Inline: the output and the probes read it at every step.
inline double Simulation::stored_velocity(MatSlot s) const {
    const CompiledLevel& lv = model_.levels[s.level];
    return (lv.x()[s.index] - lv.x_prev()[s.index]) / lv.dt;
}

// Inline: read by the bowed chain's loop as a probe.
inline double Simulation::power_in() const {
    double p = 0;
    for (const auto& lv : model_.levels)
        for (const auto& g : lv.gestures) p += g.power;
    return p;
}

// Inline: read after every step, by the bowed chain's loop too.
inline double Simulation::output() const {
    double sum = 0;
    for (const auto& o : model_.outputs) {
        double v = 0;
        switch (o.signal) {
            case Output::Signal::Position:
                v = stored_position(o.mat);
                break;
            case Output::Signal::Velocity:
                v = stored_velocity(o.mat);
                break;
            case Output::Signal::Force:
                v = model_.levels[o.mat.level].watched_force[o.watched];
                break;
        }
        sum += o.gain * v;
    }
    return model_.output_gain * sum;
}

// Inline: the bow and the finger solve with them at every step.
// How far MAT s moves per newton over a step: T²/m, or its modes' for a modal point.
inline double Simulation::response(const CompiledLevel& lv, int s) const {
    const int point = lv.modal_point_of[s];
    return point < 0 ? lv.coeff[s] : lv.modal_points[point].coeff;
}

// Adds the motion a force on MAT s causes over this step.
inline void Simulation::push(CompiledLevel& lv, int s, double force) {
    const int point = lv.modal_point_of[s];
    if (point < 0)
        lv.x_next()[s] += lv.coeff[s] * force;
    else if (force != 0.0)
        apply_modal_force(lv, point, force);
}

// A finger's or a bow's two forces, on MATs a and b, pushed as push() does. Where a modal point
// reads a plain one of them (a wide bow's contact reads three string masses), the points then
// follow their modes before anything reads them; a push on a modal point has moved the points
// sharing its modes itself.
inline void Simulation::push_pair(CompiledLevel& lv, int a, double force_a, int b, double force_b) {
    push(lv, a, force_a);
    push(lv, b, force_b);
    if (lv.read_by_point[a] || lv.read_by_point[b]) update_modal_points(lv);
}

// A faster link sees a slower MAT move along a straight line over the MAT's period, from
// its previous position to its newest (a first-order hold): a gesture point then moves
// smoothly at the link's rate instead of in steps its damper would feel as spikes. The
// newest position is the one for the end of the period (the MAT computed it a period
// ahead), so a gesture track or a simulated slower mass are followed without delay.
inline double Simulation::seen_position(MatSlot s, CompiledCrossLink::EndRate rate,
                                        bool between_steps) const {
    if (rate != CompiledCrossLink::EndRate::Slower) return stored_position(s);
    const CompiledLevel& lv = model_.levels[s.level];
    double done = period_done_[s.level];
    if (between_steps) {  // the next step's view
        const int period = lv.divider, countdown = countdown_[s.level];
        done = countdown == 0 ? 1.0 : static_cast<double>(period - countdown) / period;
    }
    const double from = lv.x_prev()[s.index], to = lv.x()[s.index];
    return from + (to - from) * done;
}

}  // namespace archet
