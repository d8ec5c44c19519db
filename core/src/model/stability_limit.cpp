#include "archet/model/stability_limit.hpp"

#include <algorithm>
#include <cmath>

#include "archet/model/linear_system.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/stability.hpp"

namespace archet {

namespace {
// Puts the probed parameter back however the probing ends.
class Restore {
  public:
    Restore(double& field) : field_(field), value_(field) {}
    ~Restore() { field_ = value_; }
    Restore(const Restore&) = delete;
    Restore& operator=(const Restore&) = delete;

  private:
    double& field_;
    double value_;
};
}  // namespace

std::optional<StabilityLimit> stability_limit(Model& model, const ParameterName& name) {
    const Mat* mat = model.find_mat(name.element);
    const Lia* lia = model.find_lia(name.element);
    // The bow's buffer acts only in contact: its linear bound is no limit to show.
    if ((!mat && !lia) || (lia && lia->kind == LiaKind::BowFriction)) return std::nullopt;
    const ParameterInfo info = parameter_info(model, name);
    if (!info.stability_relevant) return std::nullopt;
    const bool upper = parameter_role(model, name) != ParameterRole::Mass;  // K, Z grow to it
    const std::string rate = mat ? mat->rate : lia->rate;
    double& field = parameter_field(model, name);
    const Restore restore(field);
    auto stable_at = [&](double v) {
        field = v;  // probed in place: no copy of the model
        try {
            return analyse_stability(assemble_linear_system(model, rate, Fingers::Exclude))
                .stable();
        } catch (const std::exception&) {
            return true;  // nothing linear at that level moves: nothing to go unstable
        }
    };
    StabilityLimit limit;
    limit.upper = upper;
    limit.current = field;
    if (!stable_at(limit.current)) return std::nullopt;
    // Bracket the limit by factors of 4 (in the direction that destabilises, up to the end of
    // the parameter's range), then bisect on a log scale: the parameters span many decades.
    double good = limit.current > 0 ? limit.current : (upper ? 1e-9 : 1.0);
    double bad = good;
    for (int i = 0; i < 80; ++i) {
        bad = upper ? std::min(bad * 4, info.maximum) : bad / 4;
        if (!stable_at(bad)) break;
        if (bad == info.maximum || i == 79) return std::nullopt;  // never unstable this way
        good = bad;
    }
    while (std::abs(std::log(bad / good)) > 1e-6) {
        const double middle = std::sqrt(good * bad);
        (stable_at(middle) ? good : bad) = middle;
    }
    limit.value = good;
    return limit;
}

std::optional<StabilityLimit> stability_limit(const Model& model, const ParameterName& name) {
    Model trial = model;
    return stability_limit(trial, name);
}

}  // namespace archet
