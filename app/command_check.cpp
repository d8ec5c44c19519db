// `archet check`: what a model holds, its rate levels and stability margins, its first
// mode, and every problem found.

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/stability.hpp"
#include "commands.hpp"
#include "option_checks.hpp"

namespace archet::cli {

namespace {

struct CheckArguments {
    std::string model;
    std::vector<std::string> set;
    double sample_rate = 0;
};

std::string counts(const std::map<std::string, int>& by_kind) {
    std::string out;
    for (const auto& [kind, n] : by_kind)
        out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + kind;
    return out;
}

int run_check(const CheckArguments& a) {
    Model model = load_model_file(a.model);
    for (const auto& s : a.set) apply_assignment(model, s);
    if (a.sample_rate > 0) model.sample_rate = a.sample_rate;
    std::map<std::string, int> mats, lias;
    for (const auto& m : model.mats) ++mats[to_string(m.kind)];
    for (const auto& l : model.lias) ++lias[to_string(l.kind)];
    std::printf("model      %s\n", model.name.c_str());
    if (!model.description.empty()) std::printf("           %s\n", model.description.c_str());
    std::printf("MAT        %zu (%s)\n", model.mats.size(), counts(mats).c_str());
    std::printf("LIA        %zu (%s)\n", model.lias.size(), counts(lias).c_str());
    std::printf("controls   %zu, probes %zu, outputs %zu, gesture %s\n", model.controls.size(),
                model.probes.size(), model.outputs.size(),
                model.gesture ? ("\"" + model.gesture->name() + "\"").c_str() : "none");

    const auto problems = find_model_problems(model);
    const bool structural =
        !problems.empty() && problems.front().message.find("unstable") == std::string::npos;
    if (!structural) {
        std::printf("rate levels\n");
        for (const auto& r : analyse_stability(model)) {
            const RateLevel* level = model.find_rate(r.rate);
            int in_level = 0;
            for (const auto& m : model.mats) in_level += m.rate == r.rate;
            std::printf(
                "  %-8s %8.1f Hz (divider %d), %d MAT: largest normalised eigenvalue %.4g of 4, "
                "margin %.1f %%%s%s\n",
                r.rate.c_str(), model.sample_rate / level->divider, level->divider, in_level,
                r.largest_eigenvalue, 100.0 * r.margin(),
                r.stiffest_dof.empty() ? "" : ", stiffest ", r.stiffest_dof.c_str());
        }
        const LinearSystem string = sounding_part(model);
        if (string.size() > 0 && string.size() <= kMaxModalDofs) {
            const ModalAnalysis modes = analyse_modes(string, model);
            if (modes.fundamental > 0)
                std::printf(
                    "first mode %.6f Hz: the string's fundamental (support modes of bridges set "
                    "aside)\n",
                    modes.fundamental);
            std::printf("lowest modes of the %d-DOF part that sounds (around \"%s\"):\n",
                        string.size(), string.dofs.front().c_str());
            for (std::size_t i = 0; i < std::min<std::size_t>(modes.modes.size(), 5); ++i) {
                const ModeInfo& m = modes.modes[i];
                std::printf(
                    "  %12.6f Hz  T60 %-8.3g %s\n", m.frequency, m.t60,
                    m.support ? "support" : ("partial " + std::to_string(m.partial)).c_str());
            }
        } else if (string.size() > kMaxModalDofs) {
            std::printf(
                "modes      not computed: %d degrees of freedom (the modal analysis handles %d)\n",
                string.size(), kMaxModalDofs);
        }
    }
    if (problems.empty()) {
        std::printf("problems   none\n");
        return 0;
    }
    std::printf("problems   %zu\n", problems.size());
    for (const auto& p : problems) std::printf("  %s: %s\n", p.where.c_str(), p.message.c_str());
    return 2;
}

}  // namespace

void add_check_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<CheckArguments>();
    auto* cmd = app.add_subcommand(
        "check", "Describe a model: elements, rate levels, stability, first mode, problems");
    cmd->add_option("model", a->model, "Model file (.json)")->required();
    cmd->add_option("--set", a->set, "Override a parameter: ID.PARAM=VALUE (repeatable)");
    cmd->add_option("--sample-rate", a->sample_rate, "Master clock (Hz; default: the model's)")
        ->check(sample_rate_range());
    cmd->callback([&action, a] { action = [a] { return run_check(*a); }; });
}

}  // namespace archet::cli
