#include "archet/bowed_string.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "archet/discrete_modes.hpp"
#include "archet/input_error.hpp"
#include "archet/linear_system.hpp"
#include "archet/model_validation.hpp"
#include "archet/stability.hpp"

namespace archet {

namespace {

constexpr int kMinMasses = 25;
constexpr int kMaxMasses = 60;
constexpr double kPreferredMargin = 0.05;  // keep 5 % of the stability bound in reserve

std::string fmt(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

std::string mass_id(int i) {
    return "s" + std::to_string(i);
}

// The string alone: bridges and chain, link stiffness k and damping z.
Model string_model(const BowedStringOptions& o, int n, double k, double z) {
    const double length = std::sqrt(o.tension / o.linear_density) / (2.0 * o.pitch);
    const double string_mass = o.linear_density * length;
    const double m = string_mass / n;
    const double bridge_mass = o.bridge_mass_ratio * string_mass;
    const double omega_b = 2.0 * std::numbers::pi * o.bridge_frequency;
    Model model;
    model.sample_rate = o.sample_rate;
    model.rates = {{"audio", 1}, {"haptic", o.haptic_divider}};
    auto bridge = [&](const std::string& id, double x) {
        Mat b;
        b.id = id, b.kind = MatKind::Oscillator, b.rate = "audio";
        b.mass = bridge_mass;
        b.stiffness = bridge_mass * omega_b * omega_b;
        b.damping = 2.0 * o.bridge_damping_ratio * bridge_mass * omega_b;
        b.display = {{x, 0.0}};
        return b;
    };
    model.mats.push_back(bridge("bridge", 0.0));
    for (int i = 1; i <= n; ++i) {
        Mat s;
        s.id = mass_id(i), s.kind = MatKind::Mass, s.rate = "audio", s.mass = m;
        s.display = {{40.0 * i, 0.0}};
        model.mats.push_back(s);
    }
    model.mats.push_back(bridge("nut", 40.0 * (n + 1)));
    for (int i = 0; i <= n; ++i) {
        Lia l;
        l.id = "k" + std::to_string(i);
        l.kind = z > 0 ? LiaKind::SpringDamper : LiaKind::Spring;
        l.rate = "audio";
        l.from = i == 0 ? "bridge" : mass_id(i);
        l.to = i == n ? "nut" : mass_id(i + 1);
        l.stiffness = k, l.damping = z;
        model.lias.push_back(l);
    }
    return model;
}

// The string's first mode: the one nearest the pitch. (The two bridges add their own modes
// far below it, one of them raised by the string's stiffness between them.)
double first_mode(const Model& m, double pitch) {
    double best = 0;
    for (const auto& mode : discrete_modes(assemble_linear_system(m, "audio")))
        if (std::abs(mode.frequency - pitch) < std::abs(best - pitch)) best = mode.frequency;
    return best;
}

// Link stiffness (and damping) that put the string's first discrete mode on the pitch.
Model tuned_string(const BowedStringOptions& o, int n) {
    const double length = std::sqrt(o.tension / o.linear_density) / (2.0 * o.pitch);
    const double m = o.linear_density * length / n;
    const double dt = 1.0 / o.sample_rate;
    // Fixed–fixed discrete chain: sin(Ω1·T/2) = √(K·T²/m)·sin(π/(2(N+1))).
    const double ratio =
        std::sin(std::numbers::pi * o.pitch * dt) / std::sin(std::numbers::pi / (2.0 * (n + 1)));
    double k = m / (dt * dt) * ratio * ratio;
    auto damping_for = [&](double stiffness) {
        if (o.string_damping >= 0.0) return o.string_damping;
        // Damping proportional to stiffness: mode 1 decays at σ = (z/2K)·ω1².
        const double omega = 2.0 * std::numbers::pi * o.pitch;
        return 2.0 * stiffness * std::log(1000.0) / (o.string_t60 * omega * omega);
    };
    Model model = string_model(o, n, k, damping_for(k));
    for (int iteration = 0; iteration < 30; ++iteration) {
        const double f = first_mode(model, o.pitch);
        if (f <= 0.0) break;
        if (std::abs(f / o.pitch - 1.0) < 1e-13) break;
        k *= (o.pitch / f) * (o.pitch / f);
        model = string_model(o, n, k, damping_for(k));
    }
    return model;
}

void add_bow(Model& model, const BowedStringOptions& o, int n) {
    const int bowed = std::clamp(static_cast<int>(std::lround(o.bow_position * (n + 1))), 1, n / 2);
    const std::string string_mass = mass_id(bowed);
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
    model.outputs = {{"bridge", Output::Signal::Force, 1.0}};
    model.output_gain = o.output_gain;
}

Model assemble(const BowedStringOptions& o, int n) {
    Model model = tuned_string(o, n);
    add_bow(model, o, n);
    std::ostringstream name, description;
    name << "bowed-string-" << fmt(o.pitch);
    const int bowed = std::clamp(static_cast<int>(std::lround(o.bow_position * (n + 1))), 1, n / 2);
    description << "Homogeneous chaplet of " << n << " masses tuned to " << fmt(o.pitch)
                << " Hz, bowed at mass " << bowed
                << " (beta = " << fmt(static_cast<double>(bowed) / (n + 1))
                << "), heavy damped bridges, sound from the bridge force.";
    model.name = name.str();
    model.description = description.str();
    if (o.with_gesture) model.gesture = steady_bow_gesture();
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
    require(o.masses == 0 || (o.masses >= kMinMasses && o.masses <= kMaxMasses), "--masses",
            "must be " + std::to_string(kMinMasses) + " to " + std::to_string(kMaxMasses) +
                " (the paper's chaplets)");
    require(o.bow_position > 0 && o.bow_position < 0.5, "--bow-position",
            "beta must be in (0, 0.5)");
    require(std::isfinite(o.string_damping), "--string-damping",
            "must be a finite number of N·s/m");
    require(o.string_t60 > 0, "--string-t60", "must be positive seconds");
    require(o.haptic_divider >= 1, "--haptic-divider", "must be at least 1");
    require(o.mu_s > 0 && o.mu_d >= 0 && o.mu_d <= o.mu_s, "--mu-s/--mu-d",
            "need 0 <= mu_d <= mu_s and mu_s > 0");
    require(o.v0 > 0, "--v0", "must be positive m/s");
}

}  // namespace

void add_bow_module(Model& model, const BowedStringOptions& o, const std::string& string_mass) {
    auto mat = [](const std::string& id, MatKind kind, const std::string& rate, double mass) {
        Mat m;
        m.id = id, m.kind = kind, m.rate = rate, m.mass = mass;
        return m;
    };
    Mat hand_slide = mat("hand_slide", MatKind::Gesture, "haptic", 0);
    hand_slide.axis = GestureAxis::Slide;
    Mat hand_press = mat("hand_press", MatKind::Gesture, "haptic", 0);
    hand_press.axis = GestureAxis::Press;
    model.mats.push_back(mat("bow", MatKind::Mass, "audio", o.bow_mass));
    model.mats.push_back(mat("bow_press", MatKind::Mass, "audio", o.press_mass));
    model.mats.push_back(mat("surface", MatKind::Fixed, "audio", 0));
    model.mats.push_back(hand_slide);
    model.mats.push_back(hand_press);

    auto hold = [](const std::string& id, const std::string& from, const std::string& to, double k,
                   double z) {
        Lia l;
        l.id = id, l.kind = LiaKind::SpringDamper, l.rate = "haptic";
        l.from = from, l.to = to, l.stiffness = k, l.damping = z;
        return l;
    };
    model.lias.push_back(hold("bow_hold", "hand_slide", "bow", o.bow_stiffness, o.bow_damping));
    model.lias.push_back(
        hold("press_hold", "hand_press", "bow_press", o.press_stiffness, o.press_damping));
    Lia friction;
    friction.id = "friction", friction.kind = LiaKind::BowFriction, friction.rate = "audio";
    friction.from = "bow", friction.to = string_mass, friction.press = "bow_press",
    friction.surface = "surface";
    friction.stiffness = o.buffer_stiffness, friction.damping = o.buffer_damping;
    friction.mu_static = o.mu_s, friction.mu_dynamic = o.mu_d, friction.v0 = o.v0;
    model.lias.push_back(friction);
}

int max_stable_masses(double pitch, double sample_rate) {
    // Highest chain mode ≈ (N+1)·f0·2/π·... ; exact: 4K_n·sin²(Nπ/(2(N+1))) < 4 with
    // √K_n = sin(π f0 T)/sin(π/(2(N+1))).
    int best = 0;
    for (int n = 1; n <= 10000; ++n) {
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

Model build_bowed_string(const BowedStringOptions& o) {
    check_options(o);
    const int limit = max_stable_masses(o.pitch, o.sample_rate);
    auto explain = [&](const std::string& what) {
        return what + ": a homogeneous chain of N masses tuned to " + fmt(o.pitch) +
               " Hz puts its highest mode near " + "(N+1)·" + fmt(o.pitch) +
               " Hz, and the explicit scheme needs every mode below fs/π (ω·T < 2); at " +
               fmt(o.sample_rate) + " Hz that allows at most " + std::to_string(limit) +
               " masses. Lower the pitch or raise --sample-rate.";
    };
    if (o.masses > 0) {
        Model m = assemble(o, o.masses);
        if (stability_use(m) >= 1.0)
            throw InputError("--masses", explain(std::to_string(o.masses) + " masses at " +
                                                 fmt(o.pitch) + " Hz are unstable"));
        validate_model(m);
        return m;
    }
    if (limit < kMinMasses)
        throw InputError("--pitch", explain("no chaplet of " + std::to_string(kMinMasses) + "–" +
                                            std::to_string(kMaxMasses) + " masses is stable at " +
                                            fmt(o.pitch) + " Hz"));
    // The largest count that keeps a reserve; the smallest stable one otherwise.
    for (int n = std::min(kMaxMasses, limit); n >= kMinMasses; --n) {
        Model m = assemble(o, n);
        if (stability_use(m) <= 1.0 - kPreferredMargin || n == kMinMasses) {
            if (stability_use(m) >= 1.0) break;
            validate_model(m);
            return m;
        }
    }
    throw InputError("--pitch", explain("no stable chaplet at " + fmt(o.pitch) + " Hz"));
}

Gesture steady_bow_gesture(double speed, double press, double duration) {
    const double land = 0.03, accelerate = 0.1, lift = duration - 0.4;
    std::vector<GestureKeyframe> k;
    k.push_back({0.0, 0.0, 0.0});     // bow resting on the string
    k.push_back({land, 0.0, press});  // lands
    k.push_back({land + accelerate / 2, speed * accelerate / 8, press});  // speeds up
    k.push_back({land + accelerate, speed * accelerate / 2, press});
    const double x_lift = speed * accelerate / 2 + speed * (lift - land - accelerate);
    k.push_back({lift, x_lift, press});                          // steady stroke
    k.push_back({lift + 0.05, x_lift + speed * 0.025, -0.002});  // lifts off
    k.push_back({duration, x_lift + speed * 0.025, -0.002});
    return Gesture("steady bow", std::move(k));
}

}  // namespace archet
