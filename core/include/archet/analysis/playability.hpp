#pragma once
// Playability maps (Schelleng diagrams) for any bowed model: a steady stroke played over a grid
// of bow force and bow position, each run classified from its slip velocity and its sound, and
// Schelleng's lines drawn from the model's own string for comparison.

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "archet/analysis/string_first_mode.hpp"
#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"
#include "archet/physics/chain_kernel.hpp"

namespace archet {

enum class Regime {
    Helmholtz,     ///< one stick and one slip per period at the string's pitch
    MultipleSlip,  ///< several slips per period, still periodic at the pitch (too little force)
    Raucous,       ///< aperiodic (too much force)
    AnomalousLow,  ///< periodic well below the pitch: a period of two or three string periods
    Silent,        ///< no sustained oscillation
};
const char* to_string(Regime regime);
/// Throws InputError for an unknown name.
Regime regime_from_string(const std::string& name);

struct RegimeAnalysis {
    Regime regime = Regime::Silent;
    double slips_per_period = 0;
    double pitch_cents = 0;  ///< the slip period against the string's first mode
    double slip_share = 0;   ///< fraction of time slipping
    double centroid = 0;     ///< Hz, spectral centroid of the sound
};

/// Classifies a steady stretch of bowing: `slip` (bow minus string, m/s) and `sound` at `fs`;
/// `pitch` is the string's first mode.
RegimeAnalysis classify_regime(const std::vector<double>& slip, const std::vector<double>& sound,
                               double fs, double pitch);

struct MapPoint {
    std::size_t index = 0;  ///< in the grid: force-major
    double force = 0;       ///< N, the bow's normal force (steady)
    double position = 0;    ///< β
    RegimeAnalysis analysis;
};

struct MapGrid {
    double force_min = 0.01, force_max = 1, position_min = 0.06, position_max = 0.2;
    int force_steps = 8, position_steps = 5;  ///< forces log-spaced, positions linear
    double speed = 0.1;                       ///< m/s, bow speed
    double duration = 1.0;                    ///< s of steady bowing per run
    std::size_t size() const;
    double force(std::size_t index) const;
    double position(std::size_t index) const;
    /// "force=MIN:MAX:STEPS position=MIN:MAX:STEPS speed=V duration=S" (the CSV's first line).
    std::string describe() const;
    static MapGrid parse(const std::string& description);
};

/// What a grid point plays: `model` with its bow at the point's position and, for its probes, the
/// bow's slip velocity alone (what a map reads after every tick, which Simulation::run() reads in
/// the bowed chain's loop; probes change nothing of the motion), and the steady stroke at the
/// point's force.
struct MapStroke {
    Model variant;
    Gesture stroke;
};
MapStroke map_stroke(const Model& model, const MapGrid& grid, std::size_t index);

/// Plays one grid point on `model` (a bowed string with a hand on each axis). `pitch` is the
/// string's first mode (0: string_first_mode()). With `sound`, the whole stroke's output.
/// `build`: the bowed chain loop's (Simulation::set_chain_build()), else the widest here.
MapPoint play_map_point(const Model& model, const MapGrid& grid, std::size_t index,
                        double pitch = 0, std::vector<double>* sound = nullptr,
                        std::optional<ChainBuild> build = std::nullopt);

/// The build of the bowed chain's loop that plays the map's first point fastest
/// (fastest_chain_build()).
ChainBuild fastest_build_for_map(const Model& model, const MapGrid& grid);

/// Schelleng's bounds at one bow position and speed: below `minimum` several slips per
/// period, above `maximum` raucous (both zero for a model without a string to read).
struct SchellengBounds {
    double minimum = 0, maximum = 0;
};

/// What Schelleng's lines need of the model's string: its impedance Z0 = √(k·m) at the bow,
/// μs − μd, and the loss resistance R = 2·Z0·f1·τ of its first mode's decay. Reading them
/// takes the string's first mode (string_first_mode()); the bounds at each position are then
/// a formula.
struct SchellengLines {
    double impedance = 0, resistance = 0, friction_drop = 0;
    SchellengBounds at(double position, double speed) const;
};

/// A map's points, sorted by index, with what it read of the model's first mode, found once (on
/// a long string that takes as long as several points): the pitch its points are measured
/// against, and Schelleng's lines to draw over them.
struct PlayedMap {
    std::vector<MapPoint> points;
    double first_mode = 0;  ///< Hz
    SchellengLines lines;
};

/// Plays the points of `grid` whose index % shards == shard on `jobs` threads, calling
/// `progress(done, total)` from the caller's thread as they finish. Setting `*cancel` stops it
/// (InputError "cancelled").
PlayedMap play_map(const Model& model, const MapGrid& grid, int jobs, int shard = 0, int shards = 1,
                   const std::function<void(std::size_t, std::size_t)>& progress = {},
                   const std::atomic<bool>* cancel = nullptr);

/// How flat or sharp a map's Helmholtz points play against the string's first mode: the
/// pitch flattening that grows with bow force.
struct HelmholtzPitch {
    int points = 0;  ///< Helmholtz points in the map (the range is 0 … 0 without any)
    double flattest = 0, sharpest = 0;  ///< cents
};
HelmholtzPitch helmholtz_pitch(const std::vector<MapPoint>& points);

/// The steady normal force (N) a press of the hand's pressure axis gives, and its bow
/// position β (the bowed mass's place along the string).
double force_for_press(const Model& model, double press);
double bow_position(const Model& model);

SchellengLines schelleng_lines(const Model& model);
/// The same from the string's first mode, when the caller has it (string_first_mode(model)).
SchellengLines schelleng_lines(const Model& model, const StringFirstMode& first);
/// schelleng_lines(model).at(position, speed).
SchellengBounds schelleng_bounds(const Model& model, double position, double speed);

/// The map as CSV (first line: "# archet-map " + grid.describe()), with Schelleng's bounds at
/// each point from `lines`; and back.
std::string format_map(const MapGrid& grid, const std::vector<MapPoint>& points,
                       const SchellengLines& lines);
std::pair<MapGrid, std::vector<MapPoint>> parse_map(const std::string& text,
                                                    const std::string& source);

}  // namespace archet
