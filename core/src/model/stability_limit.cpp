#include "archet/model/stability_limit.hpp"

#include <cmath>

#include "archet/model/linear_system.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/stability.hpp"

namespace archet {

std::optional<StabilityLimit> stability_limit(const Model& model, const std::string& element,
                                              const std::string& parameter) {
    const bool upper = parameter == "stiffness" || parameter == "damping";
    if (!upper && parameter != "mass") return std::nullopt;
    const Mat* mat = model.find_mat(element);
    const Lia* lia = model.find_lia(element);
    if ((!mat && !lia) || (lia && lia->kind == LiaKind::BowFriction)) return std::nullopt;
    const std::string rate = mat ? mat->rate : lia->rate;
    Model trial = model;
    auto stable_at = [&](double v) {
        set_parameter(trial, element, parameter, v);
        try {
            return analyse_stability(assemble_linear_system(trial, rate)).stable();
        } catch (const std::exception&) {
            return true;  // nothing linear at that level moves: nothing to go unstable
        }
    };
    StabilityLimit limit;
    limit.upper = upper;
    limit.current = get_parameter(model, element, parameter);
    if (!stable_at(limit.current)) return std::nullopt;
    // Bracket the limit by factors of 4 (in the direction that destabilises), then bisect on a
    // log scale: the parameters span many decades.
    double good = limit.current > 0 ? limit.current : (upper ? 1e-9 : 1.0);
    double bad = good;
    for (int i = 0; i < 80; ++i) {
        bad = upper ? bad * 4 : bad / 4;
        if (!stable_at(bad)) break;
        good = bad;
        if (i == 79) return std::nullopt;  // it never goes unstable this way
    }
    while (std::abs(std::log(bad / good)) > 1e-6) {
        const double middle = std::sqrt(good * bad);
        (stable_at(middle) ? good : bad) = middle;
    }
    limit.value = good;
    return limit;
}

}  // namespace archet
