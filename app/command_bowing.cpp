// `archet bowing`: plays one or more models with a gesture and reports how they speak: the
// bow's first contact, the time to steady Helmholtz motion (the paper's Fig. 2), slips per
// period, pitch against the first mode, and slip share. For comparing strings side by side.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "archet/analysis/attack.hpp"
#include "archet/analysis/bow_probes.hpp"
#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/run_ticks.hpp"
#include "archet/physics/simulation.hpp"
#include "commands.hpp"
#include "model_loading.hpp"

namespace archet::cli {

namespace {

struct BowingArguments {
    std::vector<std::string> models;
    std::string gesture;
    std::vector<std::string> set;
    bool json = false;
};

struct Report {
    std::string name;
    double pitch = 0;
    AttackAnalysis attack;
    AttackTransient transient;  ///< as `archet attack` counts it, from the first slip
    BowingAnalysis steady;
};

// The transient of the stroke from the bow's first contact to its last, in periods of f1,
// judged as `archet attack` judges one (with no cap on its length).
AttackTransient judge_stroke(const std::vector<double>& slip, const std::vector<double>& normal,
                             double fs, double pitch) {
    std::size_t first = 0, last = normal.size();
    while (first < last && !(normal[first] > 0)) ++first;
    while (last > first && !(normal[last - 1] > 0)) --last;
    const std::vector<Slip> slips = slips_in(slip, fs, first, last);
    const int longest = static_cast<int>((last - first) / fs * pitch) + 1;
    AttackTransient t = judge_transient(slips, 1.0 / pitch, 0.0, longest);
    if (!t.decided) t.kind = AttackKind::Never;
    return t;
}

Report play(const std::string& path, const BowingArguments& a) {
    const Model model = load_validated_model(path, a.set);
    std::optional<Gesture> gesture;
    if (!a.gesture.empty())
        gesture = load_gesture_file(a.gesture);
    else if (model.gesture)
        gesture = model.gesture;
    if (!gesture) throw InputError(path, "has no gesture of its own; give one with --gesture");
    Model probed = model;  // reading its bow's slip velocity and normal force at every tick
    if (!read_bow_only(probed, {ProbeKind::SlipVelocity, ProbeKind::NormalForce}))
        throw InputError(path, "has no bow_friction link to analyse");
    Simulation sim(compile(probed));
    sim.set_gesture_track(&*gesture);

    Report r;
    r.name = model.name;
    r.pitch = string_first_mode(model).frequency;
    const double fs = sim.sample_rate();
    std::vector<double> slip, normal;
    const auto frames = static_cast<std::size_t>(gesture->duration() * fs);
    {
        const DenormalGuard no_denormals;
        run_ticks(sim, frames, [&](std::size_t, double, const double* row) {
            slip.push_back(row[0]), normal.push_back(row[1]);
            return true;
        });
    }
    r.attack = analyse_attack(slip, normal, fs, r.pitch);
    r.transient = judge_stroke(slip, normal, fs, r.pitch);
    // The steady part: from Helmholtz onset (or half a second after contact) to the last
    // contact, less a few periods for the lift.
    std::size_t last = normal.size();
    while (last > 0 && !(normal[last - 1] > 0)) --last;
    last =
        last > static_cast<std::size_t>(0.05 * fs) ? last - static_cast<std::size_t>(0.05 * fs) : 0;
    const double start =
        r.attack.reached() ? r.attack.helmholtz : std::max(0.0, r.attack.contact) + 0.5;
    r.steady = analyse_bowing(slip, fs, r.pitch, static_cast<std::size_t>(start * fs), last);
    return r;
}

int run_bowing(const BowingArguments& a) {
    std::vector<Report> reports;
    for (const auto& m : a.models) reports.push_back(play(m, a));
    if (a.json) {
        nlohmann::ordered_json out = nlohmann::ordered_json::array();
        for (const auto& r : reports) {
            const bool settled = r.attack.reached() && r.steady.helmholtz();
            out.push_back(
                {{"model", r.name},
                 {"pitch", r.pitch},
                 {"contact", r.attack.contact},
                 {"helmholtz", settled ? nlohmann::ordered_json(r.attack.helmholtz) : nullptr},
                 {"attack", settled ? nlohmann::ordered_json(r.attack.attack()) : nullptr},
                 {"attack_kind", to_string(r.transient.kind)},
                 {"transient", to_string(r.transient.transient)},
                 {"transient_periods", r.transient.kind == AttackKind::Never
                                           ? nullptr
                                           : nlohmann::ordered_json(r.transient.periods)},
                 {"slips_per_period", r.steady.slips_per_period},
                 {"pitch_cents", r.steady.pitch_cents},
                 {"slip_share", r.steady.slip_share},
                 {"helmholtz_motion", r.steady.helmholtz()}});
        }
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    std::printf("%-30s %10s %9s %10s %8s %-14s %12s %8s %10s %s\n", "model", "f1 Hz", "contact s",
                "attack ms", "periods", "transient", "slips/period", "cents", "slip share",
                "Helmholtz");
    for (const auto& r : reports) {
        std::printf("%-30s %10.3f %9.4f ", r.name.c_str(), r.pitch, r.attack.contact);
        if (r.attack.reached() && r.steady.helmholtz())
            std::printf("%10.1f", 1e3 * r.attack.attack());
        else
            std::printf("%10s", "never");
        if (r.transient.kind == AttackKind::Never)
            std::printf(" %8s", "never");
        else
            std::printf(" %8.1f", r.transient.periods);
        std::printf(" %-14s", to_string(r.transient.transient));
        std::printf(" %12.3f %+8.1f %10.3f %s\n", r.steady.slips_per_period, r.steady.pitch_cents,
                    r.steady.slip_share, r.steady.helmholtz() ? "yes" : "no");
    }
    return 0;
}

}  // namespace

void add_bowing_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<BowingArguments>();
    auto* cmd = app.add_subcommand(
        "bowing",
        "Play models with a gesture; report attack time to Helmholtz motion, slips, pitch");
    cmd->add_option("models", a->models, "Model files (.json) to compare")->required();
    cmd->add_option("--gesture", a->gesture, "Gesture file (default: each model's own gesture)");
    cmd->add_option("--set", a->set,
                    "Override a parameter in every model: ID.PARAM=VALUE (repeatable)");
    cmd->add_flag(
        "--json", a->json,
        "Print JSON: contact, helmholtz, attack (s), attack_kind, transient, transient_periods, "
        "slips_per_period, pitch_cents, slip_share");
    cmd->callback([&action, a] { action = [a] { return run_bowing(*a); }; });
}

}  // namespace archet::cli
