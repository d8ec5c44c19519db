#include "archet/analysis/playability.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <sstream>
#include <unsupported/Eigen/FFT>

#include "archet/analysis/bow_probes.hpp"
#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/common/grid_sweep.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/model/string_points.hpp"
#include "archet/physics/chain_build_choice.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/run_ticks.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

const char* to_string(Regime r) {
    switch (r) {
        case Regime::Helmholtz:
            return "helmholtz";
        case Regime::MultipleSlip:
            return "multiple_slip";
        case Regime::Raucous:
            return "raucous";
        case Regime::AnomalousLow:
            return "anomalous_low";
        case Regime::Silent:
            return "silent";
    }
    return "?";
}

Regime regime_from_string(const std::string& name) {
    for (Regime r : {Regime::Helmholtz, Regime::MultipleSlip, Regime::Raucous, Regime::AnomalousLow,
                     Regime::Silent})
        if (name == to_string(r)) return r;
    throw InputError(name,
                     "is not a regime (helmholtz, multiple_slip, raucous, anomalous_low, "
                     "silent)");
}

namespace {

// Normalised autocorrelation of the (mean-free) signal at `lag` samples.
double autocorrelation(const std::vector<double>& x, std::size_t lag) {
    if (lag == 0 || lag >= x.size() / 2) return 0;
    double mean = 0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(x.size());
    double xy = 0, xx = 0, yy = 0;
    for (std::size_t i = 0; i + lag < x.size(); ++i) {
        const double a = x[i] - mean, b = x[i + lag] - mean;
        xy += a * b, xx += a * a, yy += b * b;
    }
    return xx > 0 && yy > 0 ? xy / std::sqrt(xx * yy) : 0;
}

double spectral_centroid(const std::vector<double>& x, double fs) {
    std::size_t n = 1;
    while (2 * n <= x.size() && n < (1u << 16)) n *= 2;
    if (n < 64) return 0;
    std::vector<double> windowed(n);
    const std::size_t start = x.size() - n;
    for (std::size_t i = 0; i < n; ++i)
        windowed[i] = x[start + i] * 0.5 * (1 - std::cos(2 * std::numbers::pi * i / n));
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> bins;
    fft.fwd(bins, windowed);
    double weighted = 0, total = 0;
    for (std::size_t k = 1; k < n / 2; ++k) {
        const double magnitude = std::abs(bins[k]);
        weighted += magnitude * static_cast<double>(k) * fs / n, total += magnitude;
    }
    return total > 0 ? weighted / total : 0;
}

const Lia& bow_module(const Model& model) {
    if (const Lia* bow = first_bow(model)) return *bow;
    throw InputError(model.name, "has no bow module (bow_friction) to map");
}

// Newtons of steady normal force per metre of the hand's pressure axis: the hand's link and
// the bow's buffer in series.
double press_stiffness(const Model& model) {
    const Lia& bow = bow_module(model);
    for (const auto& l : model.lias) {
        if (l.kind == LiaKind::BowFriction) continue;
        const std::string other = l.from == bow.press ? l.to : l.to == bow.press ? l.from : "";
        const Mat* hand = model.find_mat(other);
        if (!hand || hand->kind != MatKind::Gesture || hand->axis != GestureAxis::Press) continue;
        const double series = l.stiffness * bow.stiffness / (l.stiffness + bow.stiffness);
        return series * hand->position_scale;
    }
    throw InputError(model.name,
                     "has no hand on the bow's pressure axis (a gesture point with "
                     "axis press linked to \"" +
                         bow.press + "\")");
}

double first_mode(const Model& model, const StringFirstMode& first) {
    if (!(first.frequency > 0))
        throw InputError(model.name, "has no string mode to measure pitch against");
    return first.frequency;
}

}  // namespace

RegimeAnalysis classify_regime(const std::vector<double>& slip, const std::vector<double>& sound,
                               double fs, double pitch) {
    RegimeAnalysis r;
    if (slip.size() < 16 || sound.size() < 16) return r;
    const BowingAnalysis a = analyse_bowing(slip, fs, pitch, 0, slip.size());
    r.slips_per_period = a.slips_per_period;
    r.pitch_cents = a.pitch_cents;
    r.slip_share = a.slip_share;
    r.centroid = spectral_centroid(sound, fs);
    if (a.slips_per_period < 0.2) return r;  // sticking, or off the string: silent
    const auto lag = static_cast<std::size_t>(std::lround(fs / pitch));
    const double r1 = autocorrelation(sound, lag);
    const double r_low = std::max(autocorrelation(sound, 2 * lag), autocorrelation(sound, 3 * lag));
    const bool periodic = r1 > 0.8;
    if (a.helmholtz() ||
        (periodic && std::abs(a.slips_per_period - 1) < 0.1 && std::abs(a.pitch_cents) < 50))
        r.regime = Regime::Helmholtz;
    else if (periodic && a.slips_per_period >= 1.4)
        r.regime = Regime::MultipleSlip;
    else if (!periodic && r_low > 0.8)
        r.regime = Regime::AnomalousLow;
    else
        r.regime = Regime::Raucous;
    return r;
}

std::size_t MapGrid::size() const {
    return static_cast<std::size_t>(force_steps) * static_cast<std::size_t>(position_steps);
}

double MapGrid::force(std::size_t index) const {
    const auto i = static_cast<int>(index) / position_steps;
    if (force_steps == 1) return force_min;
    return force_min * std::pow(force_max / force_min, static_cast<double>(i) / (force_steps - 1));
}

double MapGrid::position(std::size_t index) const {
    const auto j = static_cast<int>(index) % position_steps;
    if (position_steps == 1) return position_min;
    return position_min + (position_max - position_min) * j / (position_steps - 1);
}

std::string MapGrid::describe() const {
    std::ostringstream s;
    s.precision(17);
    s << "force=" << force_min << ":" << force_max << ":" << force_steps
      << " position=" << position_min << ":" << position_max << ":" << position_steps
      << " speed=" << speed << " duration=" << duration;
    return s.str();
}

MapGrid MapGrid::parse(const std::string& text) {
    MapGrid g;
    std::istringstream words(text);
    std::string word;
    auto range = [&](const std::string& value, double& lo, double& hi, int& steps) {
        char c1 = 0, c2 = 0;
        std::istringstream v(value);
        if (!(v >> lo >> c1 >> hi >> c2 >> steps) || c1 != ':' || c2 != ':')
            throw InputError(value, "expected MIN:MAX:STEPS");
    };
    while (words >> word) {
        const auto eq = word.find('=');
        const std::string key = word.substr(0, eq),
                          value = eq == std::string::npos ? "" : word.substr(eq + 1);
        if (key == "force")
            range(value, g.force_min, g.force_max, g.force_steps);
        else if (key == "position")
            range(value, g.position_min, g.position_max, g.position_steps);
        else if (key == "speed")
            g.speed = std::stod(value);
        else if (key == "duration")
            g.duration = std::stod(value);
    }
    return g;
}

MapStroke map_stroke(const Model& model, const MapGrid& grid, std::size_t index) {
    Model variant = model;
    set_variant_parameter(variant, "bow.position", grid.position(index));
    if (!read_bow_only(variant, {ProbeKind::SlipVelocity}))
        throw InputError(variant.name, "has no bow to play a map with");
    validate_model(variant);
    Gesture stroke = steady_bow_gesture(grid.speed, grid.force(index) / press_stiffness(variant),
                                        grid.duration + 0.4);  // lifts after `duration`
    return {std::move(variant), std::move(stroke)};
}

MapPoint play_map_point(const Model& model, const MapGrid& grid, std::size_t index, double pitch,
                        std::vector<double>* whole, std::optional<ChainBuild> build) {
    MapPoint p;
    p.index = index;
    p.force = grid.force(index);
    p.position = grid.position(index);
    const auto [variant, stroke] = map_stroke(model, grid, index);
    if (!(pitch > 0)) pitch = first_mode(variant, string_first_mode(variant));
    Simulation sim(compile(variant));
    sim.set_gesture_track(&stroke);
    if (build) sim.set_chain_build(*build);
    const DenormalGuard no_denormals;
    const auto total = static_cast<std::size_t>(grid.duration * sim.sample_rate());
    const std::size_t from = total / 2;  // the attack is over by half-way
    std::vector<double> slip, sound;
    slip.reserve(total - from), sound.reserve(total - from);
    if (whole) whole->clear();
    run_ticks(sim, total, [&](std::size_t tick, double sample, const double* row) {
        if (whole) whole->push_back(sample);
        if (tick >= from) slip.push_back(row[0]), sound.push_back(sample);
        return true;
    });
    p.analysis = classify_regime(slip, sound, sim.sample_rate(), pitch);
    return p;
}

ChainBuild fastest_build_for_map(const Model& model, const MapGrid& grid) {
    const auto [variant, stroke] = map_stroke(model, grid, 0);
    Simulation sim(compile(variant));
    sim.set_gesture_track(&stroke);
    return fastest_chain_build(sim);
}

PlayedMap play_map(const Model& model, const MapGrid& grid, int jobs, int shard, int shards,
                   const std::function<void(std::size_t, std::size_t)>& progress,
                   const std::atomic<bool>* cancel) {
    shard_points(grid.size(), shard, shards);  // a bad shard is refused before anything runs
    // A model without a bow is told so in those words, before its modes are analysed.
    bow_module(model);
    PlayedMap map;
    // One analysis for the points' pitch and the lines (the bow's position does not move the
    // modes).
    const StringFirstMode first = string_first_mode(model);
    map.first_mode = first_mode(model, first);
    map.lines = schelleng_lines(model, first);
    // Every variant is checked before the threads start.
    for (double beta : {grid.position_min, grid.position_max}) {
        Model check = model;
        set_variant_parameter(check, "bow.position", beta);
        press_stiffness(check);
    }
    // The build of the bowed chain's loop that plays the first point fastest plays them all (they
    // differ in the bow's place and force alone), found before the threads start.
    const ChainBuild build = fastest_build_for_map(model, grid);
    map.points = sweep_grid<MapPoint>(
        model.name, grid.size(), jobs, shard, shards,
        [&](std::size_t index) {
            return play_map_point(model, grid, index, map.first_mode, nullptr, build);
        },
        progress, cancel);
    return map;
}

HelmholtzPitch helmholtz_pitch(const std::vector<MapPoint>& points) {
    HelmholtzPitch h;
    for (const auto& p : points) {
        if (p.analysis.regime != Regime::Helmholtz) continue;
        const double cents = p.analysis.pitch_cents;
        h.flattest = h.points ? std::min(h.flattest, cents) : cents;
        h.sharpest = h.points ? std::max(h.sharpest, cents) : cents;
        ++h.points;
    }
    return h;
}

double force_for_press(const Model& model, double press) {
    return press * press_stiffness(model);
}

double bow_position(const Model& model) {
    const std::string centre = bowed_centre(model, bow_module(model));
    const std::vector<std::string> stations = bow_stations(model);
    const auto bowed = std::find(stations.begin(), stations.end(), centre);
    return bowed == stations.end() ? 0.0
                                   : static_cast<double>(bowed - stations.begin() + 1) /
                                         static_cast<double>(stations.size() + 1);
}

SchellengLines schelleng_lines(const Model& model) {
    bow_module(model);  // a model without a bow is told so before its modes are analysed
    return schelleng_lines(model, string_first_mode(model));
}

SchellengLines schelleng_lines(const Model& model, const StringFirstMode& first) {
    const Lia& bow = bow_module(model);
    const std::string centre = bowed_centre(model, bow);
    const Mat* bowed = model.find_mat(centre);
    double k = 0;
    for (const auto& id : string_links(model)) {
        const Lia* l = model.find_lia(id);
        if (l->from == centre || l->to == centre) k = std::max(k, l->stiffness);
    }
    const double t60 = first.t60;
    SchellengLines lines;
    if (!bowed || !(k > 0) || !(t60 > 0) || !std::isfinite(t60)) return lines;
    lines.impedance = std::sqrt(k * bowed->mass);
    lines.resistance = 2 * lines.impedance * first.frequency * t60 / std::log(1000.0);
    lines.friction_drop = bow.mu_static - bow.mu_dynamic;
    return lines;
}

SchellengBounds SchellengLines::at(double position, double speed) const {
    SchellengBounds b;
    if (!(impedance > 0)) return b;
    const double z0 = impedance, r = resistance, dmu = friction_drop;
    b.maximum = 2 * z0 * speed / (position * dmu);
    b.minimum = z0 * z0 * speed / (2 * r * position * position * dmu);
    return b;
}

SchellengBounds schelleng_bounds(const Model& model, double position, double speed) {
    return schelleng_lines(model).at(position, speed);
}

std::string format_map(const MapGrid& grid, const std::vector<MapPoint>& points,
                       const SchellengLines& lines) {
    std::ostringstream s;
    s.precision(10);
    s << "# archet-map " << grid.describe() << "\n";
    s << "index,force_n,position,regime,slips_per_period,pitch_cents,slip_share,centroid_hz,"
         "schelleng_min_n,schelleng_max_n\n";
    for (const auto& p : points) {
        const SchellengBounds b = lines.at(p.position, grid.speed);
        s << p.index << "," << p.force << "," << p.position << "," << to_string(p.analysis.regime)
          << "," << p.analysis.slips_per_period << "," << p.analysis.pitch_cents << ","
          << p.analysis.slip_share << "," << p.analysis.centroid << "," << b.minimum << ","
          << b.maximum << "\n";
    }
    return s.str();
}

std::pair<MapGrid, std::vector<MapPoint>> parse_map(const std::string& text,
                                                    const std::string& source) {
    std::istringstream lines(text);
    std::string line;
    if (!std::getline(lines, line) || line.rfind("# archet-map ", 0) != 0)
        throw InputError(source, "is not an archet map (it must start with \"# archet-map\")");
    const MapGrid grid = MapGrid::parse(line.substr(13));
    std::getline(lines, line);  // the column names
    std::vector<MapPoint> points;
    int row = 2;
    while (std::getline(lines, line)) {
        ++row;
        if (line.empty()) continue;
        std::istringstream cells(line);
        std::string cell;
        std::vector<std::string> c;
        while (std::getline(cells, cell, ',')) c.push_back(cell);
        if (c.size() < 8) throw InputError(source, "row " + std::to_string(row) + " is short");
        MapPoint p;
        try {
            p.index = std::stoul(c[0]);
            p.force = std::stod(c[1]), p.position = std::stod(c[2]);
            p.analysis.regime = regime_from_string(c[3]);
            p.analysis.slips_per_period = std::stod(c[4]), p.analysis.pitch_cents = std::stod(c[5]);
            p.analysis.slip_share = std::stod(c[6]), p.analysis.centroid = std::stod(c[7]);
        } catch (const std::logic_error&) {
            throw InputError(source,
                             "row " + std::to_string(row) + " has a value that is not a number");
        }
        if (p.index >= grid.size())
            throw InputError(source, "row " + std::to_string(row) + " is outside the grid");
        points.push_back(p);
    }
    return {grid, points};
}

}  // namespace archet
