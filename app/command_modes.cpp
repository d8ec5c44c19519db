// `archet modes`: the modes of a model's linear part, exact for the scheme at its rate.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/common/input_error.hpp"
#include "commands.hpp"
#include "model_loading.hpp"

namespace archet::cli {

namespace {

struct ModesArguments {
    std::string model;
    std::vector<std::string> set;
    bool json = false;
    int limit = 0;
};

// Probes that read a MAT: the mode shapes are shown there.
std::vector<std::pair<std::string, std::string>> shape_columns(const Model& model,
                                                               const ModalAnalysis& modes) {
    std::vector<std::pair<std::string, std::string>> columns;
    for (const auto& p : model.probes) {
        const bool on_mat = p.kind == ProbeKind::Position || p.kind == ProbeKind::Velocity ||
                            p.kind == ProbeKind::Force;
        if (on_mat && modes.has_shape_at(p.element)) columns.emplace_back(p.id, p.element);
    }
    return columns;
}

int run_modes(const ModesArguments& a) {
    if (a.limit < 0) throw InputError("--limit", "must be 0 (all) or a positive count");
    const Model model = load_validated_model(a.model, a.set);
    const ModalAnalysis modes = analyse_modes(model);
    const auto columns = shape_columns(model, modes);
    const std::size_t shown =
        a.limit > 0 ? std::min<std::size_t>(a.limit, modes.modes.size()) : modes.modes.size();
    if (a.json) {
        nlohmann::ordered_json out;
        out["model"] = model.name;
        out["rate"] = modes.rate;
        out["sample_rate"] = modes.sample_rate;
        out["dofs"] = modes.dofs.size();
        out["fundamental"] = modes.fundamental;
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        for (std::size_t i = 0; i < shown; ++i) {
            const auto& m = modes.modes[i];
            nlohmann::ordered_json j{
                {"index", i + 1},
                {"frequency", m.frequency},
                {"t60", std::isfinite(m.t60) ? nlohmann::ordered_json(m.t60) : nullptr},
                {"kind", m.support ? "support" : "string"}};
            if (!m.support) j["partial"] = m.partial, j["cents"] = m.cents;
            nlohmann::ordered_json shape = nlohmann::ordered_json::object();
            for (const auto& [probe, element] : columns) shape[probe] = modes.shape_at(m, element);
            j["shape"] = shape;
            list.push_back(j);
        }
        out["modes"] = list;
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    std::printf(
        "modes of \"%s\": %zu degrees of freedom at rate level \"%s\" (%.0f Hz), f1 = %.6f Hz\n",
        model.name.c_str(), modes.dofs.size(), modes.rate.c_str(), modes.sample_rate,
        modes.fundamental);
    std::printf("%5s  %-7s %14s %10s %7s %9s", "#", "kind", "frequency Hz", "T60 s", "partial",
                "cents");
    for (const auto& [probe, element] : columns) std::printf(" %12.12s", probe.c_str());
    std::printf("\n");
    for (std::size_t i = 0; i < shown; ++i) {
        const auto& m = modes.modes[i];
        std::printf("%5zu  %-7s %14.6f %10.4g", i + 1, m.support ? "support" : "string",
                    m.frequency, m.t60);
        if (m.support)
            std::printf(" %7s %9s", "-", "-");
        else
            std::printf(" %7d %+9.2f", m.partial, m.cents);
        for (const auto& [probe, element] : columns)
            std::printf(" %+12.4f", modes.shape_at(m, element));
        std::printf("\n");
    }
    return 0;
}

}  // namespace

void add_modes_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<ModesArguments>();
    auto* cmd = app.add_subcommand(
        "modes", "Modes of a model's linear part: frequency, T60, cents against n·f1, shapes");
    cmd->add_option("model", a->model, "Model file (.json)")->required();
    cmd->add_option("--set", a->set, "Override a parameter: ID.PARAM=VALUE (repeatable)");
    cmd->add_option("--limit", a->limit, "Show the lowest N modes only (0 = all)")
        ->capture_default_str();
    cmd->add_flag(
        "--json", a->json,
        "Print JSON: rate, sample_rate, fundamental, modes[frequency, t60, partial, cents, shape]");
    cmd->callback([&action, a] { action = [a] { return run_modes(*a); }; });
}

}  // namespace archet::cli
