#pragma once
// Attack maps (Guettler diagrams): how a bowed string starts a note. The bow starts from rest
// at a constant force and a constant acceleration; each attack is judged by how many periods
// pass from the first slip until steady Helmholtz motion (one slip per period of the string)
// and by what the transient was. Guettler, Acta Acustica 88 (2002); Woodhouse, Euphonics §9.5.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "archet/analysis/bowing_analysis.hpp"
#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"

namespace archet {

/// What the start of an attack did: nothing irregular, or its first irregular period.
enum class Transient {
    None,          ///< Helmholtz motion from the first slip
    MultipleSlip,  ///< a period with more than one slip (too little force)
    Prolonged,     ///< a period longer than the string's (too much force)
    Sliding,       ///< the bow slid for most of a period, or never gripped again (far too
                   ///< little force)
    Stuck,         ///< the bow never slipped: it dragged the string along (far too much force)
};
const char* to_string(Transient transient);
/// Throws InputError for an unknown name.
Transient transient_from_string(const std::string& name);

/// How the attack ended.
enum class AttackKind {
    Perfect,       ///< Helmholtz motion from the first slip
    MultipleSlip,  ///< Helmholtz motion after a transient of too little force: its first
                   ///< irregular period held a second slip, or the bow slid through most of it
    Prolonged,     ///< Helmholtz motion after a transient that began with a prolonged period
    Never,         ///< no steady Helmholtz motion within the periods allowed
};
const char* to_string(AttackKind kind);
/// Throws InputError for an unknown name.
AttackKind attack_kind_from_string(const std::string& name);

struct AttackTransient {
    AttackKind kind = AttackKind::Never;
    Transient transient = Transient::Stuck;
    double periods = 0;    ///< from the first slip to steady Helmholtz motion, in periods of f1
    int slips = 0;         ///< slips in that transient (in the periods allowed, for Never)
    bool decided = false;  ///< the slips seen so far settle it
};

/// Judges an attack from its slips (in order) against the string's period (s). A period is
/// steady when it lasts within `tolerance`·period of the string's and its slip lasts less than
/// half of it (Slip::slid_through). Steady Helmholtz motion starts at the first slip followed
/// by `settle` steady periods, at most `periods_max` periods after the first slip. The
/// transient is named by its first period that is not steady: a second slip in it, else a slip
/// through most of it, else too long. `now` (s) is how far the stroke has been played: a
/// transient that has not settled by then is Never only once no later start could count.
AttackTransient judge_transient(const std::vector<Slip>& slips, double period, double now,
                                int periods_max, int settle = 10, double tolerance = 0.1);

/// The attack protocol's timing (s): the press ramps up from 0 to its full value over
/// kPressRamp, holds still until kBowStart, and from then the hand slides with constant
/// acceleration. A stroke that has not slipped kNoSlipWait after the bow started is Never.
inline constexpr double kPressRamp = 0.02, kBowStart = 0.05, kNoSlipWait = 1.0;

/// The protocol as a gesture, in device units: keyframes every `step` seconds (the hand's
/// rate) on the parabola slide = ½·a·(t − kBowStart)², up to `duration`.
Gesture attack_gesture(double press, double acceleration, double step, double duration);

/// The default grid spans the boundary between too little and too much force on the shipped
/// strings (0.25–0.65 N at 1 m/s²; 3–7 N at 40 m/s² on the 220 and 440 Hz strings), on log
/// axes, where a wedge from the origin is a band.
struct AttackGrid {
    double acceleration_min = 1, acceleration_max = 40;  ///< m/s², of the hand
    int acceleration_steps = 16;
    double force_min = 0.05, force_max = 10;  ///< N, the bow's steady normal force
    int force_steps = 16;
    bool log_axes = true;  ///< log-spaced grid (else linear)
    double position = 0;   ///< β; 0 keeps the model's own bow position
    int periods_max = 25;  ///< longest transient counted
    std::size_t size() const;
    double acceleration(
        std::size_t index) const;  ///< index = acceleration step · force steps + force step
    double force(std::size_t index) const;
    /// "acceleration=MIN:MAX:STEPS force=MIN:MAX:STEPS axes=linear position=B periods-max=N"
    std::string describe() const;
    static AttackGrid parse(const std::string& description);
    /// Why this grid cannot be played (e.g. "0 < MIN ≤ MAX ≤ 1000 and STEPS ≥ 1 for the
    /// acceleration (m/s²)"), or empty when it can.
    std::string problem() const;
};

struct AttackPoint {
    std::size_t index = 0;
    double acceleration = 0, force = 0;
    AttackTransient transient;
    double first_slip = -1;  ///< s from the bow's start to its first slip (−1: none)
};

/// Plays one attack on `model` (a bowed string with a hand on each axis); `pitch` is the
/// string's first mode (0: string_first_mode()). With `sound`, the stroke's output.
AttackPoint play_attack_point(const Model& model, const AttackGrid& grid, std::size_t index,
                              double pitch = 0, std::vector<double>* sound = nullptr);

/// A whole attack map: its grid, its points and the pitch its periods count.
struct AttackMap {
    AttackGrid grid;
    std::vector<AttackPoint> points;
    double pitch = 0;  ///< Hz, the string's first mode
};

/// Plays the points whose index % shards == shard on `jobs` threads, calling
/// `progress(done, total)` from the caller's thread. Sorted by index. Setting `*cancel`
/// stops it (InputError "cancelled").
AttackMap play_attack(const Model& model, const AttackGrid& grid, int jobs, int shard = 0,
                      int shards = 1,
                      const std::function<void(std::size_t, std::size_t)>& progress = {},
                      const std::atomic<bool>* cancel = nullptr);

/// The attack map as CSV: first line "# archet-attack " + grid.describe(), then comment
/// lines (the protocol and the pitch, "f1 = … Hz"), the column names with their units, one
/// row per point; and back.
std::string format_attack(const AttackMap& map);
AttackMap parse_attack(const std::string& text, const std::string& source);

}  // namespace archet
