#include "archet/model/model_validation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>

#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/model/gesture_validation.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/stability.hpp"

namespace archet {

namespace {

std::string quoted(const std::string& kind, const std::string& id) {
    return kind + " " + quoted_text(id);
}

// The element a problem is about, named in words only when there is a problem: a large model
// that passes builds none of its elements' names.
struct ElementName {
    const char* kind;
    const std::string& id;
};

class Checker {
  public:
    explicit Checker(const Model& m) : model_(m) {
        mats_.reserve(m.mats.size());
        for (const auto& mat : m.mats) mats_.emplace(mat.id, &mat);  // the first of duplicates
    }

    std::vector<ModelProblem> run() {
        check_header();
        check_ids();
        for (const auto& m : model_.mats) check_mat(m);
        for (const auto& l : model_.lias) check_lia(l);
        check_bow_sharing();
        for (const auto& c : model_.controls) check_control(c);
        check_probes();
        check_outputs();
        if (problems_.empty()) check_stability(model_, "");
        if (problems_.empty())
            for (const auto& c : model_.controls) check_control_extremes(c);
        return problems_;
    }

  private:
    void add(std::string where, std::string message) {
        problems_.push_back({std::move(where), std::move(message)});
    }
    void add(const ElementName& where, std::string message) {
        add(quoted(where.kind, where.id), std::move(message));
    }
    void problems_from(const std::optional<InputError>& error) {
        if (error) add(error->where(), error->message());
    }

    void check_header() {
        if (!(model_.sample_rate >= limits::kMinSampleRate &&
              model_.sample_rate <= limits::kMaxSampleRate))
            add("model", "sample_rate " + format_number(model_.sample_rate) +
                             " Hz is out of range; use 1000 to 1000000 Hz");
        if (!(model_.output_gain > 0.0 && model_.output_gain <= limits::kOutputGain))
            add("model", "output_gain must be above 0 and at most " +
                             format_number(limits::kOutputGain) + " (is " +
                             format_number(model_.output_gain) +
                             "); it scales the output to full scale, e.g. 1.5 for a bowed string");
        const std::size_t elements =
            model_.mats.size() + model_.lias.size() + model_.controls.size();
        if (elements > limits::kElements)
            add("model", "holds " + std::to_string(elements) +
                             " elements; a model may have at most " +
                             std::to_string(limits::kElements));
        if (model_.probes.size() > limits::kProbes)
            add("model", "has " + std::to_string(model_.probes.size()) +
                             " probes; a model may have at most " +
                             std::to_string(limits::kProbes));
        if (model_.gesture) problems_from(check_gesture(*model_.gesture, "gesture"));
        if (model_.rates.empty())
            add("model", "needs at least one rate level, e.g. {\"id\": \"audio\", \"divider\": 1}");
        std::set<std::string> seen;
        for (const auto& r : model_.rates) {
            if (r.id.empty()) add("rate level", "needs a non-empty id");
            if (!is_printable_text(r.id))
                add(quoted("rate level", r.id),
                    "an id may hold only printable characters; rename it");
            if (!seen.insert(r.id).second)
                add(quoted("rate level", r.id), "duplicate id; rename one");
            if (r.divider < 1 || r.divider > 4096)
                add(quoted("rate level", r.id),
                    "divider " + std::to_string(r.divider) + " is out of range; use 1 to 4096");
        }
    }

    void check_ids() {
        std::unordered_map<std::string_view, const char*> seen;  // id → the kind that has it
        seen.reserve(model_.mats.size() + model_.lias.size() + model_.controls.size());
        auto claim = [&](const char* kind, const std::string& id) {
            if (id.empty()) {
                add(kind, "needs a non-empty id");
                return;
            }
            if (!is_printable_text(id)) {
                add(quoted(kind, id),
                    "an id may hold only printable characters (no control characters such as "
                    "ESC or NUL); rename it");
                return;
            }
            auto [it, added] = seen.emplace(id, kind);
            if (!added)
                add(quoted(kind, id), std::string("duplicate id (also used by a ") + it->second +
                                          "); every element needs its own id");
        };
        for (const auto& m : model_.mats) claim("mass", m.id);
        for (const auto& l : model_.lias) claim("link", l.id);
        for (const auto& c : model_.controls) claim("control", c.id);
    }

    void check_rate(const ElementName& where, const std::string& rate) {
        if (!model_.find_rate(rate))
            add(where, "rate level \"" + rate +
                           "\" does not exist; declare it in \"rates\" or use one that does");
    }

    // Every parameter within its physical range (the table, element_kinds.cpp), so that no state
    // or energy of a model that passes can overflow.
    template <class Element>
    bool in_ranges(const ElementName& where, const Element& e) {
        for (const auto& p : kind_parameters(e.kind)) {
            std::string problem = range_problem(p.info, e.*p.field);
            if (!problem.empty()) return add(where, std::move(problem)), false;
        }
        return true;
    }

    void check_mat(const Mat& m) {
        const ElementName where{"mass", m.id};
        check_rate(where, m.rate);
        for (double v : {m.mass, m.position, m.velocity, m.stiffness, m.damping, m.position_scale,
                         m.force_scale})
            if (!std::isfinite(v)) {
                add(where, "has a non-finite parameter (NaN or infinity)");
                return;
            }
        if (!in_ranges(where, m)) return;  // the table's ranges, per kind
        if (m.kind == MatKind::ModalPoint) check_modal_point(where, m);
        if (m.kind == MatKind::Gesture && m.position_scale == 0.0)
            add(where, "position_scale must not be 0 (the device could not move it)");
    }

    // A modal point reads modal oscillators (masses with inertia) of its own rate level.
    void check_modal_point(const ElementName& where, const Mat& m) {
        if (m.modes.empty()) add(where, "a modal point needs at least one mode in \"modes\"");
        if (m.modes.size() != m.weights.size())
            add(where, "has " + count_of(m.modes.size(), "mode", "modes") + " but " +
                           count_of(m.weights.size(), "weight", "weights") +
                           "; give one weight (mode shape value) per mode");
        for (double w : m.weights)
            if (!std::isfinite(w)) add(where, "has a non-finite weight");
        for (const auto& id : m.modes) {
            const Mat* mode = mat_ref(where, "mode", id);
            if (!mode) continue;
            if (mode->kind != MatKind::Mass && mode->kind != MatKind::Oscillator)
                add(where, "mode " + quoted_text(id) + " is a " + to_string(mode->kind) +
                               "; modes must be masses or oscillators (with inertia)");
            else if (mode->rate != m.rate)
                add(where, "mode " + quoted_text(id) + " runs at rate \"" + mode->rate +
                               "\", the point at \"" + m.rate +
                               "\"; a modal point and its modes share one rate level");
        }
    }

    const Mat* mat_ref(const ElementName& where, const char* role, const std::string& id) {
        const auto found = mats_.find(id);
        const Mat* m = found == mats_.end() ? nullptr : found->second;
        if (!m)
            add(where, std::string(role) + " \"" + id +
                           "\" is not a mass of this model; link it to an existing mass id");
        return m;
    }

    void check_lia(const Lia& l) {
        const ElementName where{"link", l.id};
        check_rate(where, l.rate);
        for (double v : {l.stiffness, l.damping, l.length, l.mu_static, l.mu_dynamic, l.v0,
                         l.finger_position, l.pressure})
            if (!std::isfinite(v)) {
                add(where, "has a non-finite parameter (NaN or infinity)");
                return;
            }
        if (!in_ranges(where, l)) return;  // the table's ranges, per kind
        if (l.kind == LiaKind::Finger) {
            check_finger(where, l);
            return;
        }
        if (l.kind != LiaKind::BowFriction) {
            const Mat* a = mat_ref(where, "\"from\"", l.from);
            const Mat* b = mat_ref(where, "\"to\"", l.to);
            if (a && b && a == b)
                add(where,
                    "joins mass " + quoted_text(l.from) + " to itself; pick two different masses");
            if (a && b) check_rate_crossing(where, l, *a, *b);
            return;
        }
        // Beyond its range (mu_s in (0, 10], v0 in (0, 100] m/s): the one rule across two.
        if (!(l.mu_dynamic >= 0.0 && l.mu_dynamic <= l.mu_static))
            add(where, "mu_d must be in [0, mu_s] (is " + format_number(l.mu_dynamic) + ", mu_s " +
                           format_number(l.mu_static) + ")");
        const std::pair<const char*, const std::string*> roles[] = {{"\"bow\"", &l.from},
                                                                    {"\"string\"", &l.to},
                                                                    {"\"press\"", &l.press},
                                                                    {"\"surface\"", &l.surface}};
        std::set<std::string> distinct;
        const Mat* ends[4] = {};
        for (int i = 0; i < 4; ++i) {
            ends[i] = mat_ref(where, roles[i].first, *roles[i].second);
            distinct.insert(*roles[i].second);
            if (ends[i] && ends[i]->rate != l.rate)
                add(where,
                    std::string(roles[i].first) + " mass " + quoted_text(ends[i]->id) +
                        " runs at rate \"" + ends[i]->rate + "\" but the bow module at \"" +
                        l.rate +
                        "\"; the friction and the masses it joins must share one rate level");
        }
        if (distinct.size() != 4)
            add(where, "bow, string, press and surface must be four different masses");
        auto movable = [](const Mat* m) {
            return m && (m->kind == MatKind::Mass || m->kind == MatKind::Oscillator ||
                         m->kind == MatKind::ModalPoint);
        };
        if (ends[0] && ends[1] && !movable(ends[0]) && !movable(ends[1]))
            add(where, "the bow and the string cannot both be immovable; make one of them a mass");
    }

    // A finger's string: two MATs or more, each once, at the finger's rate, with inertia,
    // fixed, or a modal point (a body's bridge); a gesture point has no place along a string.
    void check_finger(const ElementName& where, const Lia& l) {
        if (l.along.size() < 2)
            add(where, "\"along\" lists " + count_of(l.along.size(), "mass", "masses") +
                           "; list the string's masses in order, from the bridge to the "
                           "nut (two or more)");
        std::set<std::string> seen;
        bool movable = false;
        for (const auto& id : l.along) {
            if (!seen.insert(id).second)
                add(where, "\"along\" lists mass " + quoted_text(id) + " twice; list each once");
            const Mat* m = mat_ref(where, "\"along\"", id);
            if (!m) continue;
            if (m->kind == MatKind::Gesture)
                add(where, "\"along\" lists " + quoted_text(id) +
                               ", a gesture point; a finger touches the string's masses, "
                               "oscillators, modal and fixed points");
            else if (m->rate != l.rate)
                add(where, "\"along\" lists " + quoted_text(id) + " at rate \"" + m->rate +
                               "\" but the finger runs at \"" + l.rate +
                               "\"; a finger and its string share one rate level");
            movable = movable || m->kind != MatKind::Fixed;
        }
        // Two points that share modes would move together under the finger's force, which
        // its solve takes as two independent responses: one modal point per finger.
        const auto modal = std::count_if(l.along.begin(), l.along.end(), [&](const auto& id) {
            const auto found = mats_.find(id);
            return found != mats_.end() && found->second->kind == MatKind::ModalPoint;
        });
        if (modal > 1)
            add(where, "\"along\" lists " + std::to_string(modal) +
                           " modal points; a finger may touch one (a body's bridge)");
        for (const auto& id : l.along)
            if (const auto found = mats_.find(id);
                found != mats_.end() && found->second->kind == MatKind::ModalPoint)
                for (const auto& mode : found->second->modes)
                    if (seen.count(mode))
                        add(where, "\"along\" lists " + quoted_text(mode) + ", a mode of " +
                                       quoted_text(id) + " it also lists; list one of them");
        if (l.along.size() >= 2 && seen.size() == l.along.size() && !movable)
            add(where,
                "\"along\" lists only fixed points; a finger must touch a string that moves");
    }

    // A link whose MATs tick at another rate acts through a held force or a held position: a
    // zero-order hold, which delays it by half the slow period and so feeds energy into a
    // spring unless enough damping takes it out: Z >= K·T/2 (Colgate's passivity bound).
    // Except when the only slower ends are gesture points: the hand's steps are then booked
    // exactly as the hand's work, and the link is as passive as at one rate.
    void check_rate_crossing(const ElementName& where, const Lia& l, const Mat& a, const Mat& b) {
        const RateLevel* rl = model_.find_rate(l.rate);
        const RateLevel* ra = model_.find_rate(a.rate);
        const RateLevel* rb = model_.find_rate(b.rate);
        if (!rl || !ra || !rb) return;
        auto in_step = [&](const Mat& m, const RateLevel* r) {
            return r->divider == rl->divider ||
                   (r->divider > rl->divider && m.kind == MatKind::Gesture);
        };
        if (in_step(a, ra) && in_step(b, rb)) return;
        const int slowest = std::max({rl->divider, ra->divider, rb->divider});
        const double period = slowest / model_.sample_rate;
        const double needed = l.stiffness * period / 2.0;
        if (l.damping < needed)
            add(where,
                "crosses rate levels (" + quoted_text(a.rate) + ", " + quoted_text(l.rate) +
                    ", \"" + b.rate +
                    "\"): its held force adds energy unless its damping is at least K·T/2 = " +
                    format_number(needed) + " N·s/m for T = " + format_number(period) + " s (is " +
                    format_number(l.damping) +
                    "); raise its damping or run the link and its masses at one rate");
    }

    void check_bow_sharing() {
        std::map<std::string, std::string> owner;
        for (const auto& l : model_.lias) {
            if (l.kind != LiaKind::BowFriction) continue;
            for (const auto* id : {&l.from, &l.to}) {
                auto [it, added] = owner.emplace(*id, l.id);
                if (!added)
                    add(quoted("link", l.id),
                        "shares mass " + quoted_text(*id) + " with bow module \"" + it->second +
                            "\"; each mass can be rubbed by one bow module only");
            }
        }
    }

    void check_control(const Control& c) {
        const ElementName where{"control", c.id};
        check_rate(where, c.rate);
        const ParameterName& target = c.target;
        if (!model_.find_mat(target.element) && !model_.find_lia(target.element)) {
            add(where, "target element " + quoted_text(target.element) + " does not exist");
            return;
        }
        bool known = false;
        ParameterInfo info{};
        for (const auto& p : element_parameters(model_, target.element))
            if (p.name == target.parameter) known = true, info = p;
        if (!known) {
            add(where,
                quoted_text(target.element) + " has no parameter " + quoted_text(target.parameter));
            return;
        }
        for (double v : {c.gain, c.offset, c.minimum, c.maximum})
            if (!std::isfinite(v)) {
                add(where, "has a non-finite number");
                return;
            }
        if (!(c.minimum <= c.maximum)) add(where, "range minimum must not exceed its maximum");
        // Both ends within what the target accepts: the control sets values up to them.
        for (const auto& [end, value] : {std::pair{"minimum", c.minimum}, {"maximum", c.maximum}})
            if (const std::string problem = range_problem(info, value); !problem.empty())
                add(where, std::string("range ") + end + ": " + problem);
        if (c.source == Control::Source::Envelope) {
            if (c.envelope.empty()) add(where, "an envelope needs at least one point");
            for (std::size_t i = 1; i < c.envelope.size(); ++i)
                if (!(c.envelope[i].first > c.envelope[i - 1].first))
                    add(where, "envelope times must increase strictly");
        }
        if (c.source == Control::Source::Position) mat_ref(where, "source element", c.element);
    }

    // A control may take its parameter anywhere in its range: check both ends of those the
    // stability bound depends on (on a copy of the model: the checker only reads it).
    void check_control_extremes(const Control& c) {
        if (!parameter_info(model_, c.target).stability_relevant) return;
        for (double value : {c.minimum, c.maximum}) {
            Model copy = model_;
            set_parameter(copy, c.target, value);
            const auto before = problems_.size();
            check_stability(copy, "when control " + quoted_text(c.id) + " sets " + c.target.text() +
                                      " to " + format_number(value) + ", ");
            if (problems_.size() != before) return;
        }
    }

    void check_probes() {
        std::set<std::string> seen;
        for (const auto& p : model_.probes) {
            const std::string where = quoted("probe", p.id);
            if (p.id.empty() || p.id == "time")
                add(where, "needs an id other than \"time\" (it names a CSV column)");
            if (!seen.insert(p.id).second) add(where, "duplicate probe id");
            switch (p.kind) {
                case ProbeKind::Energy:
                case ProbeKind::PowerIn:
                    break;
                case ProbeKind::Position:
                case ProbeKind::Velocity:
                case ProbeKind::Force:
                    if (!model_.find_mat(p.element))
                        add(where, "element " + quoted_text(p.element) + " is not a mass");
                    break;
                default: {
                    const Lia* l = model_.find_lia(p.element);
                    if (!l || l->kind != LiaKind::BowFriction)
                        add(where,
                            "element " + quoted_text(p.element) + " is not a bow_friction link");
                }
            }
        }
    }

    void check_outputs() {
        for (std::size_t i = 0; i < model_.outputs.size(); ++i) {
            const auto& o = model_.outputs[i];
            const std::string where = "output #" + std::to_string(i + 1);
            if (!model_.find_mat(o.element))
                add(where, "element " + quoted_text(o.element) + " is not a mass");
            if (!(std::abs(o.gain) <= limits::kOutputGain))
                add(where, "gain must be a finite number within ±" +
                               format_number(limits::kOutputGain) + " (is " +
                               format_number(o.gain) + ")");
        }
    }

    void check_stability(const Model& model, const std::string& context) {
        for (const auto& r : analyse_stability(model, /*exact=*/false)) {
            if (r.stable()) continue;
            const double fs = 1.0 / r.dt;
            add(quoted("mass", r.stiffest_dof),
                context + "the model is unstable at rate level " + quoted_text(r.rate) + " (" +
                    format_number(fs) +
                    " Hz): the largest eigenvalue of the normalised stiffness M^-1/2 (K T^2 + 2 Z "
                    "T) M^-1/2 is " +
                    format_number(r.largest_eigenvalue) +
                    ", it must stay below 4. The stiffest point is this mass; "
                    "lower the stiffness or damping of its links, raise its mass, or run the level "
                    "faster");
        }
    }

    const Model& model_;
    std::unordered_map<std::string_view, const Mat*> mats_;  // lookups by id, for large models
    std::vector<ModelProblem> problems_;
};

}  // namespace

std::vector<ModelProblem> find_model_problems(const Model& model) {
    return Checker(model).run();
}

void validate_model(const Model& model) {
    const auto problems = find_model_problems(model);
    if (!problems.empty()) throw InputError(problems.front().where, problems.front().message);
}

void set_parameter_validated(Model& model, const ParameterName& name, double value) {
    const double before = get_parameter(model, name);  // throws for a bad name
    set_parameter(model, name, value);                 // throws out of range
    try {
        validate_model(model);
    } catch (const std::exception&) {
        parameter_field(model, name) = before;  // it was in force: no second check
        throw;
    }
}

}  // namespace archet
