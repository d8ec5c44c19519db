#pragma once
// A validated model compiled to flat arrays: per rate level, the MATs in contiguous storage
// (chains of links laid out consecutively so one vectorisable loop handles them), the other
// links, oscillator grounds, gesture points and bow modules as small arrays of plain structs.
// Storage index s of a level holds MAT s−1; indices 0 and size+1 are zero padding so the
// chain loop needs no edge cases.

#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "archet/model/model.hpp"
#include "archet/physics/mat_array.hpp"
#include "archet/physics/uniform_span.hpp"
#include "archet/physics/unlinked_runs.hpp"

namespace archet {

/// Where a MAT lives after compilation.
struct MatSlot {
    int level = -1;
    int index = -1;  ///< storage index within the level
};

struct CompiledLink {  ///< a two-point link between MATs of its own level
    int a = 0, b = 0;
    double k = 0, zdt = 0, length = 0;  ///< zdt = Z / T of the level
    bool contact = false;               ///< buffer: acts only while d − length > 0
    int element = -1;                   ///< index into Model::lias
};

struct CompiledCrossLink {  ///< a link whose MATs run at other rate levels
    int level = 0;
    MatSlot a, b;
    double k = 0, zdt = 0, length = 0;
    bool contact = false;
    int element = -1;
    /// How an end's rate compares with the link's: at its rate it takes the force at once;
    /// faster, it holds the force until the link's next tick; slower, it takes the link's
    /// mean force over its period and is seen moving along a line between its ticks.
    enum class EndRate { Same, Faster, Slower };
    EndRate a_rate = EndRate::Same, b_rate = EndRate::Same;
    double a_weight = 1, b_weight = 1;  ///< share of a slower end's period
    /// A hand link: a spring-damper from a slower gesture point (the hand) to a MAT at the
    /// link's rate. `hand` is the point's index in its level's gestures, else −1.
    int hand = -1;
    bool hand_is_a = true;
    MatSlot hand_slot, end_slot;  ///< a hand link's hand and other end
    double hand_sign = 1;         ///< +1 when the hand is a (d = x(a) − x(b)), else −1
    // State: the link samples its ends at its own ticks and holds its force between them.
    double d_prev = 0, force = 0;
    double d_before = 0;   ///< one tick further back, for accounting
    double hand_seen = 0;  ///< a hand link: where it saw the hand at its last tick
    double hand_force_sum = 0, hand_work_sum = 0;  ///< over the hand's period so far
    bool acting = true;                            ///< a buffer in contact at the last tick
};

/// An oscillator's spring and damper to ground; its stiffness, damping/T and rest position are
/// the level's ground_k, ground_zdt and ground_rest at `index`. Whatever changes them (or
/// T²/m) calls fold_ground() for that MAT, then split_uniform_run(): the chain loop reads
/// them folded into update_x, …, and broadcast over each run of alike MATs.
struct CompiledGround {
    int index = 0;
    int element = -1;
};

struct CompiledGesturePoint {
    int index = 0;
    GestureAxis axis = GestureAxis::Slide;
    double position_scale = 1, force_scale = 1;
    int element = -1;
    int watched = -1;  ///< index into the level's watched_force
    // State: the mean force of the model on the point over its last period, and the work
    // the hand did on the model.
    double force = 0, work = 0, power = 0;
    /// The part of `force` from faster links over this period, and the work they booked.
    double faster_links_force = 0, faster_links_work = 0;
};

struct CompiledModalPoint {  ///< x = Σ weight·x(mode); a force F on it moves each mode by weight·F
    int index = 0;           ///< storage index of the point
    std::vector<int> modes;  ///< storage indices of its modes, same level
    int first_mode = -1;     ///< modes[k] = first_mode + k when they lie so, else −1
    std::vector<double> weights;
    double coeff = 0;  ///< Σ weight²·T²/m: its displacement per newton over a step
    /// The level's modal points that share a mode with it, itself included, in order: those a
    /// force on it moves (plan_modal_moves()).
    std::vector<int> moving_with;
};

struct CompiledBow {
    int level = 0;
    int bow = 0, string = 0, press = 0, surface = 0;
    double kb = 0, zbdt = 0;  ///< pressure buffer
    double mu_s = 0, mu_d = 0, v0 = 0;
    int element = -1;
    // State of the last step:
    double normal = 0;         ///< N
    double friction = 0;       ///< N, on the string (the bow gets the opposite)
    double slip_velocity = 0;  ///< m/s, bow minus string, at the new step
    double dissipated = 0;     ///< J over the last step (never negative)
    bool sticking = false;
};

/// A finger: pressure × (k, Z) from its contact point to ground, the contact between two
/// MATs of `along` (storage indices of its level) placed by finger_contact().
struct CompiledFinger {
    int level = 0;
    std::vector<int> along;
    double k = 0, zdt = 0;  ///< at full pressure
    double position = 1, pressure = 1;
    int element = -1;
};

/// Storage begin … end − 1 (a chain link's left MAT, or a ground's MAT) whose elements are
/// element, element + 1, …: the energy accounts add their dampers' losses a run at a time.
struct ElementRun {
    int begin, end, element;
};

struct CompiledLevel {
    std::string id;
    int divider = 1;
    double inverse_divider = 1;
    double dt = 0;
    int size = 0;  ///< MATs at this level
    /// How many MATs at the end of the storage are held: the chain loop stops before them. The
    /// fixed MATs hold their position in all three buffers (the loop would write it back
    /// unchanged); the derived points after them are not stepped at all.
    int fixed_after = 0;
    int derived_after = 0;  ///< of those, the derived points (the last ones)
    /// Zeros after the storage of the arrays the chain loop uses (positions, chain links,
    /// T²/m, the folded grounds): it updates whole vectors of up to 8 MATs, the last one running
    /// past the last MAT into these zeros (which it leaves zero), and reads the vector after each
    /// (see chain_kernel.cpp).
    static constexpr int kReadAhead = 16;
    MatArray buffer[3];            ///< positions at n+1, n, n−1 by rotation
    int current = 0;               ///< which buffer holds x[n]
    MatArray coeff;                ///< T² / m, zero for immovable MATs
    MatArray mass;                 ///< kg, zero for immovable MATs
    std::vector<double> external;  ///< forces from non-chain links, N
    std::vector<double> held;      ///< forces of slower links, held between their ticks, N
    MatArray chain_k, chain_zdt, chain_length;  ///< link j joins storage j, j+1
    bool has_chain_lengths = false;             ///< any non-zero chain_length
    /// Scratch: this step's force of the chain links in chain_forces_used (the chain loop
    /// keeps none).
    std::vector<double> chain_force;
    std::vector<int> chain_forces_used;          ///< links on either side of watched MATs
    std::vector<int> chain_element;              ///< index into Model::lias, −1 for none
    std::vector<ElementRun> chain_element_runs;  ///< the chain links with an element
    std::vector<CompiledLink> links;
    std::vector<CompiledGround> grounds;
    std::vector<ElementRun> ground_runs;         ///< the grounds, elements counted among the MATs
    MatArray ground_k, ground_zdt, ground_rest;  ///< per storage index, 0 if none
    /// The update of a MAT with its ground, folded (see fold_ground()): x[n+1] =
    /// ((a·x[n] + b·x[n−1]) + e) + T²/m·(forces). Refreshed whenever T²/m or a ground changes.
    MatArray update_x, update_xp, update_rest;  ///< a, b, e per storage index
    UniformRuns uniform;  ///< kept by whatever writes the arrays above (uniform_span.hpp)
    /// MATs without chain links, which the chain loop moves by their own update: found with the
    /// level, checked again after a loaded state or a ground folded again (unlinked_runs.hpp),
    /// and left out of `uniform`.
    std::vector<UnlinkedRun> unlinked;
    std::vector<CompiledGesturePoint> gestures;
    std::vector<int> bows;     ///< indices into CompiledModel::bows
    std::vector<int> fingers;  ///< indices into CompiledModel::fingers
    std::vector<CompiledModalPoint> modal_points;
    std::vector<int> modal_point_of;  ///< storage index → index into modal_points, or −1
    /// Modal points that nothing in the step reads (no link, bow, finger, control, probe or
    /// output: a modal string's points between its ends and its bow, kept to draw its shape).
    /// The step leaves them out, at the end of the storage; Simulation::position() sums their
    /// modes when asked. Their buffers hold where they were when compiled.
    std::vector<CompiledModalPoint> derived_points;
    std::vector<int> derived_point_of;  ///< storage index → index into derived_points, or −1
    /// Storage index → 1 for a plain mass that a modal point reads as one of its modes: after
    /// a finger's or a bow's push on one, the points follow their modes (plan_modal_moves()).
    std::vector<char> read_by_point;
    std::vector<int> touched;  ///< storage indices whose `external` must be cleared
    std::vector<int> watched;  ///< storage indices whose total link force is kept
    std::vector<double> watched_force;
    std::vector<int> element_of;  ///< storage index → index into Model::mats (−1 pad)

    // The three buffers rotate; a compare is cheaper than % 3 in the hottest accessors.
    static int before(int i) { return i == 0 ? 2 : i - 1; }
    static int after(int i) { return i == 2 ? 0 : i + 1; }
    double* x() { return buffer[current].data(); }
    double* x_prev() { return buffer[before(current)].data(); }
    double* x_next() { return buffer[after(current)].data(); }
    const double* x() const { return buffer[current].data(); }
    const double* x_prev() const { return buffer[before(current)].data(); }
    const double* x_next() const { return buffer[after(current)].data(); }
};

/// Writes the position (x[n]) of each fixed MAT the chain loop stops before (fixed_after) into
/// all three buffers, a −0 as +0 as the loop wrote it: after compiling and after a state is
/// loaded (one saved before the loop stopped there may hold a zero in x[n+1]).
void hold_fixed_tail(CompiledLevel& level);

/// Sets has_chain_lengths from the chain's rest lengths, after a state is loaded or a batch of
/// live changes (Simulation::refresh_uniform_runs()): a length set back to 0 lets the chain loop
/// leave lengths out again (the same bits as subtracting zeros). O(MATs), no allocation.
void find_chain_lengths(CompiledLevel& level);

/// Σ weight²·T²/m over a modal point's modes: its displacement per newton over a step, the
/// `coeff` it keeps, again whenever a mode's mass changes.
double modal_point_response(const CompiledLevel& lv, const CompiledModalPoint& point);

/// A runtime-settable parameter resolved to its array slot.
struct ParameterSlot {
    enum class Kind {
        Mass,
        ChainK,
        ChainZ,
        ChainLength,
        LinkK,
        LinkZ,
        LinkLength,
        GroundK,
        GroundZ,
        CrossK,
        CrossZ,
        CrossLength,
        BowKb,
        BowZb,
        BowMuS,
        BowMuD,
        BowV0,
        GesturePositionScale,
        GestureForceScale,
        FixedPosition,
        FingerK,
        FingerZ,
        FingerPosition,
        FingerPressure
    };
    Kind kind = Kind::Mass;
    int level = 0;
    int index = 0;
    bool operator==(const ParameterSlot&) const = default;
};

struct CompiledControl {
    Control::Source source = Control::Source::Envelope;
    int level = 0;
    std::vector<std::pair<double, double>> envelope;
    GestureAxis axis = GestureAxis::Slide;
    MatSlot position_of;
    double gain = 1, offset = 0, minimum = 0, maximum = 0;
    ParameterSlot target;
};

struct CompiledProbe {
    std::string id;
    ProbeKind kind = ProbeKind::Position;
    MatSlot mat;
    int bow = -1;
    int watched = -1;  ///< index into the level's watched_force (Force probes)
};

struct CompiledOutput {
    MatSlot mat;
    Output::Signal signal = Output::Signal::Force;
    double gain = 1;
    int watched = -1;
};

struct CompiledModel {
    double sample_rate = 48000;
    std::vector<CompiledLevel> levels;           ///< sorted fastest first
    std::vector<CompiledCrossLink> cross_links;  ///< the hand links first
    int hand_links = 0;                          ///< how many of cross_links are hand links
    std::vector<CompiledBow> bows;
    std::vector<CompiledFinger> fingers;
    std::vector<CompiledControl> controls;
    std::vector<CompiledProbe> probes;
    std::vector<CompiledOutput> outputs;
    double output_gain = 1;
    std::unordered_map<std::string, MatSlot> mat_slots;  ///< looked up by id, never walked
    Model source;  ///< the graph it was compiled from (names, parameters)

    /// Resolves ELEMENT.PARAMETER to an array slot; throws InputError when it cannot be
    /// changed while running (initial conditions, unknown names).
    ParameterSlot resolve_parameter(const ParameterName& name) const;
};

/// The level the hand is read at: the slowest level with gesture points (null without any).
const CompiledLevel* hand_level(const CompiledModel& model);

/// Compiles a model (validate it first). `sample_rate` > 0 overrides the model's master
/// clock; all rate levels follow it.
CompiledModel compile(const Model& model, double sample_rate = 0);

}  // namespace archet
