#include "archet/builders/bowed_string.hpp"

#include <cctype>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/builders/count_search.hpp"
#include "archet/builders/string_body.hpp"
#include "archet/builders/string_chain.hpp"
#include "archet/builders/stroke_in_band.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/bow_contact.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/stability.hpp"

namespace archet {

namespace {

bool was_cancelled(const std::atomic<bool>* cancel) {
    return cancel && cancel->load();
}

constexpr int kPaperMinMasses = 25;
constexpr int kPaperMaxMasses = 60;
constexpr int kMinMasses = 4;
// The part of the stability bound kept in reserve: the paper's 5 %; 2 % for a full string,
// whose highest mode then reaches 91 % of fs/2.
constexpr double kPaperMargin = 0.05, kFullMargin = 0.02;
constexpr double kPaperOutputGain = 1.5;  // 1/N of bridge force
constexpr double kStrokePeak = 0.5;       // −6 dBFS

std::string fmt(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

std::string mass_id(int i) {
    return "s" + std::to_string(i);
}

bool wide_bow(const BowedStringOptions& o) {
    return !o.paper && !o.point_bow;
}

// The contact point of a bow with a width: ¼, ½, ¼ of the bowed mass and its neighbours (in
// the modal structure make_modal() has added it, mixing their points' mode shapes).
std::string add_contact(Model& model, const BowedStringOptions& o, int bowed) {
    if (!wide_bow(o)) return mass_id(bowed);
    if (o.structure == Structure::Modal)
        return model.find_mat(kBowContact) ? kBowContact : mass_id(bowed);
    Mat contact;
    contact.id = kBowContact, contact.kind = MatKind::ModalPoint, contact.rate = "audio";
    contact.modes = {mass_id(bowed - 1), mass_id(bowed), mass_id(bowed + 1)};
    contact.weights = {0.25, 0.5, 0.25};
    contact.display = {{40.0 * bowed, -30.0}};
    model.mats.push_back(contact);
    return contact.id;
}

void add_bow(Model& model, const BowedStringOptions& o, int n) {
    const int bowed = bowed_mass(o, n);
    const std::string string_mass = add_contact(model, o, bowed);
    add_bow_module(model, o, string_mass);
    const double bx = 40.0 * bowed;  // editor layout: the bow above its string mass
    for (auto& m : model.mats) {
        const bool press_side = m.id == "hand_press" || m.id == "bow_press" || m.id == "surface";
        if (m.id == "hand_slide" || m.id == "bow" || press_side)
            m.display = {{press_side ? bx + 80 : bx, m.kind == MatKind::Gesture ? -160.0
                                                     : m.id == "surface"        ? -40.0
                                                                                : -80.0}};
    }

    model.probes = {
        {"bow_point_x", ProbeKind::Position, string_mass},
        {"bow_point_v", ProbeKind::Velocity, string_mass},
        {"bow_v", ProbeKind::Velocity, "bow"},
        {"slip_v", ProbeKind::SlipVelocity, "friction"},
        {"normal_force", ProbeKind::NormalForce, "friction"},
        {"friction_force", ProbeKind::FrictionForce, "friction"},
        {"bridge_force", ProbeKind::Force, "bridge"},
        {"hand_force_slide", ProbeKind::Force, "hand_slide"},
        {"hand_force_press", ProbeKind::Force, "hand_press"},
        {"energy", ProbeKind::Energy, ""},
        {"power_in", ProbeKind::PowerIn, ""},
    };
    model.output_gain = o.output_gain > 0 ? o.output_gain : kPaperOutputGain;
}

// The paper's losses are link damping set while tuning; the full string's are solved on the
// tuned chain with its bridges and body, so the decays asked for are the ones heard.
StringLosses string_losses(const BowedStringOptions& o, Model& model, int n) {
    const StringElements elements = string_elements(n);
    if (o.paper || o.string_damping >= 0) {
        const Lia& link = *model.find_lia("k0");
        return {0.0, 0.5 * link.damping / link.stiffness};
    }
    const StringDecays d = string_decays(o);
    const StringLosses losses =
        solve_string_losses(model, elements, {d.low_hz, d.low_t60, "--string-t60"},
                            {d.high_hz, d.high_t60, "--string-t60-high"});
    apply_string_losses(model, elements, losses);
    return losses;
}

// The decays the built string has, every loss included, at the two frequencies; `modes` are
// its scheme's modes (discrete_modes()).
std::string decays_text(const Model& model, const BowedStringOptions& o, int n,
                        const std::vector<DiscreteMode>& modes) {
    const StringDecays d = string_decays(o);
    std::ostringstream text;
    text.precision(3);
    const char* between = "T60 ";
    for (double f : {d.low_hz, d.high_hz}) {
        const ModeDecay m = exact_string_mode_decay(model, string_elements(n), f, modes);
        text << between << std::log(1000.0) / m.rate << " s at " << std::lround(m.frequency)
             << " Hz";
        between = ", ";
    }
    return text.str();
}

Model with_bow(Model model, const BowedStringOptions& o, int n) {
    add_bow(model, o, n);
    return model;
}

void describe(Model& model, const BowedStringOptions& o, int n, const StringLosses& losses,
              const std::string& decays) {
    const int bowed = bowed_mass(o, n);
    std::ostringstream name, text;
    const bool harmonic = o.tuning == Tuning::Harmonic, modal = o.structure == Structure::Modal;
    name << "bowed-string-" << fmt(o.pitch) << (harmonic ? "-harmonic" : "")
         << (modal ? "-modal" : "") << (o.paper ? "-paper" : "");
    if (modal) text << "Modal model (" << n << " modes) of the ";
    text << (harmonic ? "harmonic" : "homogeneous") << " chaplet of " << n << " masses tuned to "
         << fmt(o.pitch) << " Hz, bowed at mass " << bowed
         << " (beta = " << fmt(static_cast<double>(bowed) / (n + 1)) << "), ";
    if (o.paper) {
        text << "the paper's link damping, heavy damped bridges, sound from the bridge force.";
    } else {
        text << "losses sigma0 = " << fmt(losses.sigma0)
             << " 1/s and sigma1 = " << fmt(losses.sigma1) << " s (" << decays << "), "
             << (o.body == "none" ? "heavy damped bridges, sound from the bridge force."
                                  : o.body + " body at the bridge, sound radiated by the body.");
    }
    if (o.finger)
        text << " A finger stops the string at " << fmt(o.finger_position)
             << " of its length from the bridge (finger.position; 1 = open).";
    std::string description = text.str();
    description[0] = static_cast<char>(std::toupper(description[0]));
    model.name = name.str();
    model.description = description;
}

// The tuned string with its losses and bridges (and body), before a bow touches it: all that
// does not depend on where it is bowed, built once for every bow position tried.
struct UnbowedString {
    Model model;
    StringLosses losses;
    std::string decays;  ///< the decays it has, for its description
    /// The roots of its audio level's update, where its tuning solved them (retune_damped()).
    std::optional<UpdateRoots> roots;
};

// `tuned` is tuned_string(o, n), when the caller has it already.
UnbowedString unbowed_string(const BowedStringOptions& o, int n,
                             std::optional<Model> tuned = std::nullopt) {
    Model model = tuned ? std::move(*tuned) : tuned_string(o, n);  // with its body
    const StringLosses losses = string_losses(o, model, n);
    if (!o.paper && o.tuning == Tuning::Harmonic && o.string_damping < 0)
        model = tuned_string(o, n, &losses);
    std::string decays;
    std::optional<UpdateRoots> roots;
    if (!o.paper) {
        roots = retune_damped(model, o, n);
        decays = decays_text(model, o, n, discrete_modes(*roots));
    }
    return {std::move(model), losses, std::move(decays), std::move(roots)};
}

// The string bowed where `o` says.
Model bowed_at(const UnbowedString& string, const BowedStringOptions& o, int n) {
    Model model = string.model;
    if (o.structure == Structure::Modal)
        make_modal(model, n, bowed_mass(o, n), string.losses, wide_bow(o));
    add_bow(model, o, n);
    if (o.finger) add_finger(model, o, n);
    describe(model, o, n, string.losses, string.decays);
    return model;
}

double stability_use(const Model& m) {
    double worst = 0;
    for (const auto& r : analyse_stability(m))
        worst = std::max(worst, r.largest_eigenvalue / StabilityReport::kLimit);
    return worst;
}

void check_options(const BowedStringOptions& o) {
    auto require = [](bool ok, const char* option, const std::string& message) {
        if (!ok) throw InputError(option, message);
    };
    require(std::isfinite(o.pitch) && o.pitch > 0, "--pitch", "must be a positive frequency in Hz");
    require(o.sample_rate >= 1000 && o.sample_rate <= 1e6, "--sample-rate",
            "must be 1000 to 1000000 Hz");
    require(o.pitch < o.sample_rate / 4, "--pitch", "must be below a quarter of the sample rate");
    if (o.paper)
        require(o.masses == 0 || (o.masses >= kPaperMinMasses && o.masses <= kPaperMaxMasses),
                "--masses",
                "must be " + std::to_string(kPaperMinMasses) + " to " +
                    std::to_string(kPaperMaxMasses) +
                    " with --paper (the paper's chaplets); leave out --paper for more");
    else
        require(o.masses == 0 || o.masses >= kMinMasses, "--masses",
                "must be at least " + std::to_string(kMinMasses) + " (0: full bandwidth)");
    require(o.bow_position > 0 && o.bow_position < 0.5, "--bow-position",
            "beta must be in (0, 0.5)");
    require(std::isfinite(o.finger_position) && o.finger_position >= 0 && o.finger_position <= 1,
            "--finger-position", "must be 0 to 1 (the sounding share of the string; 1: open)");
    require(!o.finger || o.structure == Structure::Chain, "--finger",
            "stops a chain of masses; leave out --structure modal");
    require(std::isfinite(o.string_damping), "--string-damping",
            "must be a finite number of N·s/m");
    require(std::isfinite(o.string_t60) && o.string_t60 >= 0 && o.string_t60 <= 600, "--string-t60",
            "must be 0 (the default) to 600 seconds");
    require(std::isfinite(o.string_t60_high) && o.string_t60_high >= 0 && o.string_t60_high <= 600,
            "--string-t60-high", "must be 0 (the default) to 600 seconds");
    require(std::isfinite(o.string_t60_high_hz) && o.string_t60_high_hz >= 0 &&
                o.string_t60_high_hz < o.sample_rate / 2,
            "--string-t60-high-hz", "must be 0 (the default) or a frequency below fs/2");
    require(o.string_t60_high_hz == 0 || o.string_t60_high_hz > o.pitch, "--string-t60-high-hz",
            "must be above the pitch (" + fmt(o.pitch) + " Hz)");
    if (!o.paper && o.body != "none") find_body_preset(o.body);  // names the presets if unknown
    require(std::isfinite(o.tension) && o.tension > 0 && o.tension <= 10000, "--tension",
            "must be above 0 and at most 10000 N (a violin A string: 57.1 N)");
    require(std::isfinite(o.linear_density) && o.linear_density > 0 && o.linear_density <= 1,
            "--density", "must be above 0 and at most 1 kg/m (a violin A string: 0.00072 kg/m)");
    require(o.haptic_divider >= 1, "--haptic-divider", "must be at least 1");
    require(o.mu_s > 0 && o.mu_d >= 0 && o.mu_d <= o.mu_s, "--mu-s/--mu-d",
            "need 0 <= mu_d <= mu_s and mu_s > 0");
    require(o.v0 > 0, "--v0", "must be positive m/s");
    require(std::isfinite(o.output_gain) && o.output_gain >= 0, "--output-gain",
            "must be 0 (the default: the embedded stroke at -6 dBFS) or a positive gain");
    require(std::isfinite(o.stroke_speed) && o.stroke_speed > 0 && o.stroke_speed <= 2,
            "--stroke-speed", "must be above 0 and at most 2 m/s");
}

// The scheme's limit on N at this pitch and what it means, for messages.
std::string size_limit_text(const BowedStringOptions& o, int limit) {
    const bool harmonic = o.tuning == Tuning::Harmonic;
    const std::string why =
        harmonic ? " Hz needs its N-th partial N·" + fmt(o.pitch) +
                       " Hz below fs/2 = " + fmt(o.sample_rate / 2) + " Hz"
                 : " Hz puts its highest mode near (N+1)·" + fmt(o.pitch) +
                       " Hz, and the explicit scheme needs every mode below fs/2 (ω·T < 2)";
    return std::string("a ") + (harmonic ? "harmonic" : "homogeneous") +
           " chain of N masses tuned to " + fmt(o.pitch) + why + "; at " + fmt(o.sample_rate) +
           " Hz that allows at most " + std::to_string(limit) +
           " masses. Lower the pitch or raise --sample-rate.";
}

// What to add to a refusal to bow a string that no instrument has: the default material (a violin
// A string's) at a cello's pitch is two metres long, and hardly a stroke plays it.
std::string material_hint(const BowedStringOptions& o) {
    constexpr double kLongestBowedString = 1.2;  // m: a double bass's is about 1.05
    const double length = string_length(o);
    if (length <= kLongestBowedString) return "";
    const BowedStringOptions defaults;
    const bool violin_a =
        o.tension == defaults.tension && o.linear_density == defaults.linear_density;
    return ". At --tension " + fmt(o.tension) + " N and --density " + fmt(o.linear_density) +
           " kg/m" + (violin_a ? ", a violin A string's," : "") + " this string is " +
           fmt(std::round(length * 100) / 100) +
           " m long, longer than any bowed string: give the tension and density of the string you "
           "mean (a cello's C: about 130 N and 0.0148 kg/m)";
}

// A bow rubbing one mass of a full string drives the chain's shortest waves, which a real bow's
// width averages out: it finds almost no Helmholtz band there (docs/physics.md).
std::string point_bow_hint(const BowedStringOptions& o) {
    if (!o.point_bow || o.paper) return "";
    return ". A point bow finds almost no Helmholtz band on a full-bandwidth string: leave out "
           "--point-bow (a contact as wide as a bow's hair), or build it without a stroke "
           "(--no-gesture)";
}

// The string's first mode wherever the bow is tried. A long string's analysis costs seconds,
// and its tuning has solved the roots already: where the bow leaves the sounding part as it
// was (along a chain it does), the analysis reads them. (A modal string, made from the tuned
// chain once the bow's place is known, is another system: solved anew.)
StringFirstMode first_mode_bowed(const Model& bowed, const UnbowedString& string) {
    const LinearSystem sounding = sounding_part(bowed);
    if (string.roots && identical(string.roots->system, sounding))
        return string_first_mode(*string.roots, bowed);
    return string_first_mode(sounding, bowed);
}

// The string with its stroke. A short string has few masses to bow: where the default bow
// position finds no Helmholtz band, the next mass or two may. `model` is `string` bowed where
// `o` says.
Model finished(Model model, const UnbowedString& string, const BowedStringOptions& o, int n,
               const std::atomic<bool>* cancel) {
    validate_model(model);
    if (!o.with_gesture) return model;
    const int bowed = bowed_mass(o, n);
    const std::vector<int> moves =
        o.bow_position_fixed ? std::vector<int>{0} : std::vector<int>{0, 1, -1, 2};
    for (std::size_t k = 0; k < moves.size(); ++k) {
        BowedStringOptions moved = o;
        moved.bow_position = static_cast<double>(bowed + moves[k]) / (n + 1);
        if (bowed_mass(moved, n) != bowed + moves[k]) continue;  // off the string's bowable half
        Model m = moves[k] == 0 ? model : bowed_at(string, moved, n);
        try {
            const HelmholtzBand band =
                helmholtz_band(m, first_mode_bowed(m, string), o.stroke_speed, 17, cancel);
            m.gesture = stroke_in_band(m, band, o.stroke_speed);
            if (!o.paper && !(o.output_gain > 0) && band.peak > 0)
                m.output_gain *= kStrokePeak / band.peak;  // the stroke it carries at −6 dBFS
            validate_model(m);
            return m;
        } catch (const InputError& e) {
            if (was_cancelled(cancel)) throw;
            if (k + 1 < moves.size()) continue;
            if (e.where() != "--bow-position") throw;
            // No position finds a Helmholtz band: the material or the point bow may be why.
            throw InputError(e.where(), e.message() + material_hint(o) + point_bow_hint(o));
        }
    }
    throw InputError("--bow-position", "no bow position near " + fmt(o.bow_position) +
                                           " finds a Helmholtz band; try another" +
                                           material_hint(o) + point_bow_hint(o));
}

}  // namespace

StringDecays string_decays(const BowedStringOptions& o) {
    StringDecays d;
    d.low_hz = o.pitch;
    d.high_hz =
        o.string_t60_high_hz > 0 ? o.string_t60_high_hz : (o.pitch < 1000 ? 2000.0 : 2.0 * o.pitch);
    if (o.paper) {
        d.low_t60 = o.string_t60 > 0 ? o.string_t60 : 4.0;
        return d;
    }
    d.low_t60 = o.string_t60;
    d.high_t60 = o.string_t60_high;
    return d;
}

int max_stable_masses(double pitch, double sample_rate) {
    // Highest chain mode: 4K_n·sin²(Nπ/(2(N+1))) < 4 with √K_n = sin(π f0 T)/sin(π/(2(N+1))).
    int best = 0;
    for (int n = 1; n <= 100000; ++n) {
        const double s = std::sin(std::numbers::pi * pitch / sample_rate) /
                         std::sin(std::numbers::pi / (2.0 * (n + 1)));
        const double top = std::sin(n * std::numbers::pi / (2.0 * (n + 1)));
        if (s * top < 1.0)
            best = n;
        else
            break;
    }
    return best;
}

int max_harmonic_masses(double pitch, double sample_rate) {
    // Partial N must stay below fs/2: N·f0 < fs/2.
    const int n = static_cast<int>(std::ceil(sample_rate / 2.0 / pitch)) - 1;
    return std::max(n, 0);
}

int full_bandwidth_masses(double pitch, double sample_rate, Tuning tuning, double margin) {
    const double top = std::asin(std::sqrt(1.0 - margin)) / std::numbers::pi;  // × fs
    if (tuning == Tuning::Harmonic)  // the N-th partial at N·f0
        return std::min(max_harmonic_masses(pitch, sample_rate),
                        static_cast<int>(std::floor(top * sample_rate / pitch)));
    int best = 0;
    for (int n = 1; n <= max_stable_masses(pitch, sample_rate); ++n) {
        const double s = std::sin(std::numbers::pi * pitch / sample_rate) /
                         std::sin(std::numbers::pi / (2.0 * (n + 1)));
        if (s * std::sin(n * std::numbers::pi / (2.0 * (n + 1))) <= std::sqrt(1.0 - margin))
            best = n;
    }
    return best;
}

namespace {

// The string of the count --masses asks for, refused where the scheme cannot run it.
Model string_of_given_count(const BowedStringOptions& o, int limit,
                            const std::atomic<bool>* cancel) {
    if (o.masses > limit)
        throw InputError("--masses", std::to_string(o.masses) + " masses at " + fmt(o.pitch) +
                                         (o.tuning == Tuning::Harmonic ? " Hz reach fs/2: "
                                                                       : " Hz are unstable: ") +
                                         size_limit_text(o, limit));
    const UnbowedString string = unbowed_string(o, o.masses);
    Model m = bowed_at(string, o, o.masses);
    if (stability_use(m) >= 1.0)
        throw InputError("--masses", std::to_string(o.masses) + " masses at " + fmt(o.pitch) +
                                         " Hz are unstable once damped (largest normalised "
                                         "eigenvalue " +
                                         fmt(4 * stability_use(m)) +
                                         " of 4); use fewer masses or less damping");
    return finished(std::move(m), string, o, o.masses, cancel);
}

}  // namespace

Model build_bowed_string(const BowedStringOptions& o, const std::atomic<bool>* cancel) {
    check_options(o);
    const int limit = o.tuning == Tuning::Harmonic ? max_harmonic_masses(o.pitch, o.sample_rate)
                                                   : max_stable_masses(o.pitch, o.sample_rate);
    if (o.masses > 0) return string_of_given_count(o, limit, cancel);
    const int low = o.paper ? kPaperMinMasses : kMinMasses;
    const int high =
        o.paper
            ? std::min(kPaperMaxMasses, limit)
            : std::max(low, full_bandwidth_masses(o.pitch, o.sample_rate, o.tuning, kFullMargin));
    const double margin = o.paper ? kPaperMargin : kFullMargin;
    if (limit < low)
        throw InputError("--pitch", "no chaplet of " + std::to_string(low) +
                                        " masses or more is stable at " + fmt(o.pitch) +
                                        " Hz: " + size_limit_text(o, limit));
    // The largest count that keeps a reserve; the smallest stable one otherwise. The full
    // string's losses and tuning cost seconds; its tuned chain with the bow tells first whether
    // a count keeps the reserve (the light losses hardly move it). Assumed: a count keeps it only
    // if every smaller one does (the chain's use of the stability limit grows with the count).
    // Where the tuning ends on the damped modes, the chain tuned on its undamped modes alone
    // costs a fraction of it and, with the bow, uses the limit within a fraction of the step from
    // one count to the next (0.07 % against 0.22–0.26 % at 110 Hz): it tells where the search
    // can start.
    std::map<int, Model> tuned;  // each count's tuned_string(), computed once
    std::map<int, bool> kept;    // and whether it keeps the reserve
    const auto keeps = [&](int n) {
        if (const auto known = kept.find(n); known != kept.end()) return known->second;
        bool verdict = false;
        try {
            const Model& string = tuned.emplace(n, tuned_string(o, n)).first->second;
            verdict = stability_use(with_bow(string, o, n)) <= 1.0 - margin;
        } catch (const InputError& e) {
            if (e.where() != "--tuning") throw;  // else a harmonic chain this long cannot be tuned
        }
        kept.emplace(n, verdict);
        return verdict;
    };
    const auto roughly_keeps = [&](int n) {
        try {
            return stability_use(with_bow(undamped_tuned_string(o, n), o, n)) <= 1.0 - margin;
        } catch (const InputError&) {
            return false;  // an estimate: a wrong one only costs time
        }
    };
    const auto check_cancel = [&] {
        if (was_cancelled(cancel)) throw InputError("--pitch", "cancelled");
    };
    const int start = !o.paper && tuning_ends_on_damped_modes(o)
                          ? count_search_start(low, high, roughly_keeps, keeps, check_cancel)
                          : high;
    for (int n = start; n >= low; --n) {
        check_cancel();
        std::optional<UnbowedString> string;
        Model m;
        try {
            if (!o.paper && n > low && !keeps(n)) continue;
            auto known = tuned.extract(n);
            string = unbowed_string(
                o, n, known ? std::optional(std::move(known.mapped())) : std::nullopt);
            m = bowed_at(*string, o, n);
        } catch (const InputError& e) {
            if (n == low || e.where() != "--tuning") throw;
            continue;  // a harmonic chain this long cannot be tuned at this rate; try a shorter one
        }
        if (stability_use(m) <= 1.0 - margin || n == low) {
            if (stability_use(m) >= 1.0) break;
            return finished(std::move(m), *string, o, n, cancel);
        }
    }
    throw InputError("--pitch",
                     "no stable chaplet at " + fmt(o.pitch) + " Hz: " + size_limit_text(o, limit));
}

}  // namespace archet
