#include "archet/builders/bowed_string.hpp"

#include <Eigen/Dense>
#include <cctype>
#include <cmath>
#include <numbers>
#include <sstream>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/harmonic_chain.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/stability.hpp"

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

double string_length(const BowedStringOptions& o) {
    return std::sqrt(o.tension / o.linear_density) / (2.0 * o.pitch);
}

// The string alone: bridges and the chain of `profile`, each link damped in proportion to its
// stiffness (z = ratio·k) so that damping stays proportional and the modes keep their shapes.
Model string_model(const BowedStringOptions& o, const ChainProfile& profile, double damping_ratio) {
    const int n = static_cast<int>(profile.masses.size());
    const double string_mass = o.linear_density * string_length(o);
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
        s.id = mass_id(i), s.kind = MatKind::Mass, s.rate = "audio", s.mass = profile.masses[i - 1];
        s.display = {{40.0 * i, 0.0}};
        model.mats.push_back(s);
    }
    model.mats.push_back(bridge("nut", 40.0 * (n + 1)));
    for (int i = 0; i <= n; ++i) {
        Lia l;
        l.id = "k" + std::to_string(i);
        l.kind = damping_ratio > 0 ? LiaKind::SpringDamper : LiaKind::Spring;
        l.rate = "audio";
        l.from = i == 0 ? "bridge" : mass_id(i);
        l.to = i == n ? "nut" : mass_id(i + 1);
        l.stiffness = profile.springs[i];
        l.damping = damping_ratio * profile.springs[i];
        model.lias.push_back(l);
    }
    return model;
}

// z/k for the string's links: from --string-damping (per link, or its mean for a
// non-homogeneous chain), else so that the first mode alone decays in string_t60, since
// stiffness-proportional damping makes mode 1 decay at σ = (z/2k)·ω1².
double damping_ratio(const BowedStringOptions& o, const ChainProfile& profile) {
    double mean_k = 0;
    for (double k : profile.springs) mean_k += k / profile.springs.size();
    if (o.string_damping >= 0.0) return o.string_damping / mean_k;
    const double omega = 2.0 * std::numbers::pi * o.pitch;
    return 2.0 * std::log(1000.0) / (o.string_t60 * omega * omega);
}

// Homogeneous chaplet: equal masses and links, link stiffness refined until the string's
// first mode (the one nearest the pitch: the bridges add their own far below) is the pitch.
Model homogeneous_string(const BowedStringOptions& o, int n) {
    const double m = o.linear_density * string_length(o) / n;
    const double dt = 1.0 / o.sample_rate;
    // Fixed–fixed discrete chain: sin(Ω1·T/2) = √(K·T²/m)·sin(π/(2(N+1))).
    const double ratio =
        std::sin(std::numbers::pi * o.pitch * dt) / std::sin(std::numbers::pi / (2.0 * (n + 1)));
    ChainProfile profile{std::vector<double>(n, m),
                         std::vector<double>(n + 1, m / (dt * dt) * ratio * ratio)};
    Model model = string_model(o, profile, damping_ratio(o, profile));
    for (int iteration = 0; iteration < 30; ++iteration) {
        double f = 0;
        for (const auto& mode : discrete_modes(assemble_linear_system(model, "audio")))
            if (std::abs(mode.frequency - o.pitch) < std::abs(f - o.pitch)) f = mode.frequency;
        if (f <= 0.0 || std::abs(f / o.pitch - 1.0) < 1e-13) break;
        for (double& k : profile.springs) k *= (o.pitch / f) * (o.pitch / f);
        model = string_model(o, profile, damping_ratio(o, profile));
    }
    return model;
}

// Harmonic chaplet: masses and links from the inverse eigenvalue problem so that its first
// n partials fall on k·f0. The targets are corrected for what the fixed-end solution leaves
// out (heavy but movable bridges, damping) until the simulated partials are harmonic.
Model harmonic_string(const BowedStringOptions& o, int n) {
    const double string_mass = o.linear_density * string_length(o);
    std::vector<double> targets;
    for (int k = 1; k <= n; ++k) targets.push_back(k * o.pitch);
    Model model;
    for (int iteration = 0; iteration < 40; ++iteration) {
        ChainProfile profile;
        try {
            profile =
                chain_with_eigenvalues(prewarped_eigenvalues(targets, o.sample_rate), string_mass);
        } catch (const std::domain_error& e) {
            throw InputError("--tuning", std::string("no harmonic chaplet found (") + e.what() +
                                             "); try fewer masses");
        }
        model = string_model(o, profile, damping_ratio(o, profile));
        const ModalAnalysis modes = analyse_modes(assemble_linear_system(model, "audio"), model);
        double worst = 0;
        int k = 0;
        for (const auto& mode : modes.modes) {
            if (mode.support || k >= n) continue;
            const double wanted = (k + 1) * o.pitch;
            worst = std::max(worst, std::abs(1200.0 * std::log2(mode.frequency / wanted)));
            targets[k] *= wanted / mode.frequency;
            ++k;
        }
        if (k < n)
            throw InputError("--tuning", "the harmonic chaplet lost partials; try fewer masses");
        if (worst < 1e-4) break;
        if (targets.back() >= o.sample_rate / 2) break;  // the stability check below says why
    }
    return model;
}

int bowed_mass(const BowedStringOptions& o, int n) {
    return std::clamp(static_cast<int>(std::lround(o.bow_position * (n + 1))), 1, n / 2);
}

void add_bow(Model& model, const BowedStringOptions& o, int n) {
    const int bowed = bowed_mass(o, n);
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

// The chaplet's exact modal equivalent. The free chain (masses s1..sN and the links between
// them) decomposes into modes φ_k with M⁻¹K·φ_k = λ_k·φ_k; its damping is proportional to its
// stiffness, so each mode is an independent damped oscillator (modal mass φᵀMφ, stiffness
// λ·φᵀMφ, damping ratio·λ·φᵀMφ) under the same scheme, and x = Σ φ_k·q_k holds exactly. The
// end links to the bridges and the bow act on modal points that read x at s1, sN and the
// bowing mass.
void make_modal(Model& model, int n, int bowed, double ratio) {
    Eigen::VectorXd mass(n);
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) mass[i] = model.find_mat(mass_id(i + 1))->mass;
    for (int i = 1; i < n; ++i) {  // link k_i joins s_i and s_(i+1)
        const double ki = model.find_lia("k" + std::to_string(i))->stiffness;
        k(i - 1, i - 1) += ki, k(i, i) += ki, k(i - 1, i) -= ki, k(i, i - 1) -= ki;
    }
    const Eigen::VectorXd scale = mass.cwiseSqrt().cwiseInverse();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(scale.asDiagonal() * k *
                                                          scale.asDiagonal());

    const Mat nut = *model.find_mat("nut");
    const Lia end_a = *model.find_lia("k0"), end_b = *model.find_lia("k" + std::to_string(n));
    std::vector<Mat> mats{*model.find_mat("bridge")};
    std::vector<std::vector<double>> shapes(n);
    for (int mode = 0; mode < n; ++mode) {
        Eigen::VectorXd phi = scale.asDiagonal() * solver.eigenvectors().col(mode);
        phi /= phi.cwiseAbs().maxCoeff();
        const double modal_mass = phi.dot(mass.asDiagonal() * phi);
        const double lambda = std::max(0.0, solver.eigenvalues()[mode]);  // the rigid mode: 0
        Mat m;
        m.id = "mode" + std::to_string(mode + 1), m.kind = MatKind::Oscillator, m.rate = "audio";
        m.mass = modal_mass, m.stiffness = lambda * modal_mass,
        m.damping = ratio * lambda * modal_mass;
        m.display = {{40.0 * (mode + 1), 120.0}};
        mats.push_back(m);
        for (int i = 0; i < n; ++i) shapes[i].push_back(phi[i]);
    }
    for (int i : {1, bowed, n}) {
        Mat p;
        p.id = mass_id(i), p.kind = MatKind::ModalPoint, p.rate = "audio";
        for (int mode = 0; mode < n; ++mode) p.modes.push_back("mode" + std::to_string(mode + 1));
        p.weights = shapes[i - 1];
        p.display = {{40.0 * i, 0.0}};
        mats.push_back(p);
    }
    mats.push_back(nut);
    model.mats = mats;
    model.lias = {end_a, end_b};
}

Model assemble(const BowedStringOptions& o, int n) {
    Model model = o.tuning == Tuning::Harmonic ? harmonic_string(o, n) : homogeneous_string(o, n);
    const int bowed = bowed_mass(o, n);
    if (o.structure == Structure::Modal) {
        const Lia& link = *model.find_lia("k0");  // every link has damping = ratio·stiffness
        make_modal(model, n, bowed, link.damping / link.stiffness);
    }
    add_bow(model, o, n);
    std::ostringstream name, description;
    const bool harmonic = o.tuning == Tuning::Harmonic, modal = o.structure == Structure::Modal;
    name << "bowed-string-" << fmt(o.pitch) << (harmonic ? "-harmonic" : "")
         << (modal ? "-modal" : "");
    if (modal) description << "Modal model (" << n << " modes) of the ";
    description << (harmonic ? "harmonic" : "homogeneous") << " chaplet of " << n
                << " masses tuned to " << fmt(o.pitch) << " Hz, bowed at mass " << bowed
                << " (beta = " << fmt(static_cast<double>(bowed) / (n + 1))
                << "), heavy damped bridges, sound from the bridge force.";
    std::string text = description.str();
    text[0] = static_cast<char>(std::toupper(text[0]));
    model.name = name.str();
    model.description = text;
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

    // The hand's points tick at the haptic rate; the springs that hold the bow run at the
    // bow's rate and see the hand's steps, so the coupling is exactly passive at every step
    // (a spring at the haptic rate would hold its force, which is passive only on average).
    auto hold = [](const std::string& id, const std::string& from, const std::string& to, double k,
                   double z) {
        Lia l;
        l.id = id, l.kind = LiaKind::SpringDamper, l.rate = "audio";
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

int max_harmonic_masses(double pitch, double sample_rate) {
    // Partial N must stay below fs/2: N·f0 < fs/2.
    const int n = static_cast<int>(std::ceil(sample_rate / 2.0 / pitch)) - 1;
    return std::max(n, 0);
}

Model build_bowed_string(const BowedStringOptions& o) {
    check_options(o);
    const bool harmonic = o.tuning == Tuning::Harmonic;
    const int limit = harmonic ? max_harmonic_masses(o.pitch, o.sample_rate)
                               : max_stable_masses(o.pitch, o.sample_rate);
    auto explain = [&](const std::string& what) {
        const std::string why =
            harmonic ? " Hz needs its N-th partial N·" + fmt(o.pitch) +
                           " Hz below fs/2 = " + fmt(o.sample_rate / 2) + " Hz"
                     : " Hz puts its highest mode near (N+1)·" + fmt(o.pitch) +
                           " Hz, and the explicit scheme needs every mode below fs/π (ω·T < 2)";
        return what + ": a " + (harmonic ? "harmonic" : "homogeneous") +
               " chain of N masses tuned to " + fmt(o.pitch) + why + "; at " + fmt(o.sample_rate) +
               " Hz that allows at most " + std::to_string(limit) +
               " masses. Lower the pitch or raise --sample-rate.";
    };
    if (o.masses > 0) {
        if (o.masses > limit)
            throw InputError("--masses",
                             explain(std::to_string(o.masses) + " masses at " + fmt(o.pitch) +
                                     (harmonic ? " Hz reach fs/2" : " Hz are unstable")));
        Model m = assemble(o, o.masses);
        if (stability_use(m) >= 1.0)
            throw InputError("--masses",
                             std::to_string(o.masses) + " masses at " + fmt(o.pitch) +
                                 " Hz are unstable once damped (largest normalised eigenvalue " +
                                 fmt(4 * stability_use(m)) +
                                 " of 4); use fewer masses or less damping");
        validate_model(m);
        return m;
    }
    if (limit < kMinMasses)
        throw InputError("--pitch", explain("no chaplet of " + std::to_string(kMinMasses) + "–" +
                                            std::to_string(kMaxMasses) + " masses is stable at " +
                                            fmt(o.pitch) + " Hz"));
    // The largest count that keeps a reserve; the smallest stable one otherwise.
    for (int n = std::min(kMaxMasses, limit); n >= kMinMasses; --n) {
        Model m;
        try {
            m = assemble(o, n);
        } catch (const InputError&) {
            if (n == kMinMasses) throw;
            continue;  // a harmonic chain this long cannot be tuned at this rate; try a shorter one
        }
        if (stability_use(m) <= 1.0 - kPreferredMargin || n == kMinMasses) {
            if (stability_use(m) >= 1.0) break;
            validate_model(m);
            return m;
        }
    }
    throw InputError("--pitch", explain("no stable chaplet at " + fmt(o.pitch) + " Hz"));
}

}  // namespace archet
