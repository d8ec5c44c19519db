#include "archet/builders/string_chain.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/string_partials.hpp"
#include "archet/analysis/update_root_near.hpp"
#include "archet/builders/string_body.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/bow_contact.hpp"
#include "archet/model/linear_system.hpp"

namespace archet {

namespace {

// The paper's link damping, or damping set by hand, is on while the string is tuned.
bool damped_while_tuning(const BowedStringOptions& o) {
    return o.string_damping > 0 || (o.string_damping < 0 && o.paper);
}

std::string mass_id(int i) {
    return "s" + std::to_string(i);
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
    model.outputs = {{"bridge", Output::Signal::Force, 1.0}};
    return model;
}

// The frequency among `modes` nearest the pitch.
double nearest_frequency(const std::vector<DiscreteMode>& modes, double pitch) {
    double f = 0;
    for (const auto& mode : modes)
        if (std::abs(mode.frequency - pitch) < std::abs(f - pitch)) f = mode.frequency;
    return f;
}

// The frequency of the string's first mode: the one nearest the pitch (the bridges add their
// own far below). The paper's damped strings are tuned on the damped scheme's exact modes;
// undamped ones (losses solved later) on the string's modes of the symmetric problem, which
// is exact for them.
double first_mode(const Model& model, int n, double pitch, bool damped) {
    if (!damped) return string_mode_frequency(model, string_elements(n), pitch);
    return nearest_frequency(discrete_modes(assemble_linear_system(model, "audio")), pitch);
}

// Homogeneous chaplet: equal masses and links, link stiffness refined until the string's
// first mode is the pitch.
Model homogeneous_string(const BowedStringOptions& o, int n) {
    const double m = o.linear_density * string_length(o) / n;
    const double dt = 1.0 / o.sample_rate;
    // Fixed–fixed discrete chain: sin(Ω1·T/2) = √(K·T²/m)·sin(π/(2(N+1))).
    const double ratio =
        std::sin(std::numbers::pi * o.pitch * dt) / std::sin(std::numbers::pi / (2.0 * (n + 1)));
    ChainProfile profile{std::vector<double>(n, m),
                         std::vector<double>(n + 1, m / (dt * dt) * ratio * ratio)};
    Model model = string_model(o, profile, link_damping_ratio(o, profile));
    for (int iteration = 0; iteration < 30; ++iteration) {
        const double f = first_mode(model, n, o.pitch, damped_while_tuning(o));
        if (f <= 0.0 || std::abs(f / o.pitch - 1.0) < 1e-13) break;
        for (double& k : profile.springs) k *= (o.pitch / f) * (o.pitch / f);
        model = string_model(o, profile, link_damping_ratio(o, profile));
    }
    return model;
}

// The string's partials, ascending: on the damped scheme's modes (supports told apart by
// their shapes), or, while a string that is undamped until its losses are solved converges,
// on the symmetric problem's string modes (exact without damping, and much faster).
std::vector<double> partials(const Model& model, int n, bool damped) {
    if (!damped) return string_mode_frequencies(model, string_elements(n));
    return string_partial_frequencies(assemble_linear_system(model, "audio"), model);
}

// Harmonic chaplet: masses and links from the inverse eigenvalue problem so that its first
// n partials fall on k·f0. The targets are corrected for what the fixed-end solution leaves
// out (heavy but movable bridges, damping) until the simulated partials are harmonic.
Model harmonic_string(const BowedStringOptions& o, int n, const StringLosses* losses,
                      bool damped_steps_allowed) {
    const double string_mass = o.linear_density * string_length(o);
    std::vector<double> targets;
    for (int k = 1; k <= n; ++k) targets.push_back(k * o.pitch);
    Model model;
    // The bridges' dampers pull the lowest partials a little: the last corrections read the
    // damped modes.
    bool damped = damped_while_tuning(o) || losses;
    int damped_steps = 0;  // each reads the damped modes: a dense eigenproblem of twice the size
    for (int iteration = 0; iteration < 40; ++iteration) {
        ChainProfile profile;
        try {
            profile =
                chain_with_eigenvalues(prewarped_eigenvalues(targets, o.sample_rate), string_mass);
        } catch (const std::domain_error& e) {
            throw InputError("--tuning", std::string("no harmonic chaplet found (") + e.what() +
                                             "); try fewer masses");
        }
        model = string_model(o, profile, link_damping_ratio(o, profile));
        if (losses) apply_string_losses(model, string_elements(n), *losses);
        double worst = 0;
        int k = 0;
        damped_steps += damped;
        for (double f : partials(model, n, damped)) {
            if (k >= n) break;
            const double wanted = (k + 1) * o.pitch;
            worst = std::max(worst, std::abs(1200.0 * std::log2(f / wanted)));
            targets[k] *= wanted / f;
            ++k;
        }
        if (k < n)
            throw InputError("--tuning", "the harmonic chaplet lost partials; try fewer masses");
        if (damped && (worst < 1e-3 || damped_steps >= 4)) break;
        if (worst < 1e-4) {
            if (!damped_steps_allowed) break;
            damped = true;
        }
        if (targets.back() >= o.sample_rate / 2) break;  // the stability check says why
    }
    return model;
}

}  // namespace

double link_damping_ratio(const BowedStringOptions& o, const ChainProfile& profile) {
    double mean_k = 0;
    for (double k : profile.springs) mean_k += k / profile.springs.size();
    if (o.string_damping >= 0.0) return o.string_damping / mean_k;
    if (!o.paper) return 0.0;
    // Stiffness-proportional damping makes mode 1 decay at σ = (z/2k)·ω1².
    const double omega = 2.0 * std::numbers::pi * o.pitch;
    return 2.0 * std::log(1000.0) / (string_decays(o).low_t60 * omega * omega);
}

namespace {

// Scaling every link's stiffness and damping together moves all partials by one ratio (and
// keeps σ1): it puts the first mode on the pitch and leaves a harmonic string's other partials
// where the tuning put them.
void scale_links(Model& model, const StringElements& string, double scale) {
    for (const auto& id : string.links) {
        Lia* l = model.find_lia(id);
        l->stiffness *= scale, l->damping *= scale;
    }
}

// A body pulls the string's modes near its own and lowers the first a little: the undamped
// first mode goes back on the pitch.
void retune_with_body(Model& model, const BowedStringOptions& o, int n) {
    attach_body(model, find_body_preset(o.body));
    const StringElements string = string_elements(n);
    for (int iteration = 0; iteration < 10; ++iteration) {
        const double f = first_mode(model, n, o.pitch, false);
        if (!(f > 0) || std::abs(f / o.pitch - 1.0) < 1e-12) break;
        scale_links(model, string, (o.pitch / f) * (o.pitch / f));
    }
}

// A harmonic chaplet damped from the start of its tuning never reaches the switch to the damped
// steps, so `damped_steps_allowed` only matters where the tuning ends on the damped modes.
Model string_tuned(const BowedStringOptions& o, int n, const StringLosses* losses,
                   bool damped_steps_allowed) {
    Model model = o.tuning == Tuning::Harmonic ? harmonic_string(o, n, losses, damped_steps_allowed)
                                               : homogeneous_string(o, n);
    if (!o.paper && o.body != "none") retune_with_body(model, o, n);
    return model;
}

}  // namespace

Model tuned_string(const BowedStringOptions& o, int n, const StringLosses* losses) {
    return string_tuned(o, n, losses, true);
}

bool tuning_ends_on_damped_modes(const BowedStringOptions& o) {
    return o.tuning == Tuning::Harmonic && !damped_while_tuning(o);
}

Model undamped_tuned_string(const BowedStringOptions& o, int n) {
    return string_tuned(o, n, nullptr, false);
}

UpdateRoots retune_damped(Model& model, const BowedStringOptions& o, int n) {
    const StringElements string = string_elements(n);
    const auto on_pitch = [&](double f) { return std::abs(f / o.pitch - 1.0) < 1e-10; };
    // The scalings look at the first mode alone (update_root_near(), a millisecond where the
    // whole solve takes seconds on a low string); the whole solve, which the caller keeps,
    // then checks it, and takes over where it finds the mode elsewhere. The losses move the
    // first mode by a fraction of a cent: a root further off is another mode, left to the
    // whole solve.
    for (int scaling = 0; scaling < 4; ++scaling) {
        const LinearSystem system = assemble_linear_system(model, "audio");
        const auto z =
            update_root_near(system, std::polar(1.0, 2.0 * std::numbers::pi * o.pitch * system.dt));
        if (!z) break;
        const double f = root_frequency(*z, system.dt);
        if (!(f > 0) || on_pitch(f) || std::abs(f / o.pitch - 1.0) > 0.01) break;
        scale_links(model, string, (o.pitch / f) * (o.pitch / f));
    }
    for (int iteration = 0;; ++iteration) {  // up to four more scalings, each after a solve
        UpdateRoots roots = update_roots(assemble_linear_system(model, "audio"));
        const double f = nearest_frequency(discrete_modes(roots), o.pitch);
        if (iteration == 4 || !(f > 0) || on_pitch(f)) return roots;
        scale_links(model, string, (o.pitch / f) * (o.pitch / f));
    }
}

StringElements string_elements(int n) {
    StringElements s;
    for (int i = 1; i <= n; ++i) s.masses.push_back(mass_id(i));
    for (int i = 0; i <= n; ++i) s.links.push_back("k" + std::to_string(i));
    return s;
}

double string_length(const BowedStringOptions& o) {
    return std::sqrt(o.tension / o.linear_density) / (2.0 * o.pitch);
}

int bowed_mass(const BowedStringOptions& o, int n) {
    const int lowest = o.paper || o.point_bow ? 1 : 2;
    return std::clamp(static_cast<int>(std::lround(o.bow_position * (n + 1))), lowest,
                      std::max(lowest, n / 2));
}

// The free chain (masses s1..sN and the links between them) decomposes into modes φ_k with
// M⁻¹K·φ_k = λ_k·φ_k; its damping is proportional (2σ0·M + 2σ1·K), so each mode is an
// independent damped oscillator (modal mass φᵀMφ, stiffness λ·φᵀMφ, damping
// (2σ0 + 2σ1·λ)·φᵀMφ) under the same scheme, and x = Σ φ_k·q_k holds exactly. The end links
// to the bridges and the bow act on modal points that read x at s1, sN and the bowing mass.
void make_modal(Model& model, int n, int bowed, const StringLosses& losses, bool wide_bow) {
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

    std::vector<Mat> modes, points;
    std::vector<std::vector<double>> shapes(n);
    for (int mode = 0; mode < n; ++mode) {
        Eigen::VectorXd phi = scale.asDiagonal() * solver.eigenvectors().col(mode);
        phi /= phi.cwiseAbs().maxCoeff();
        const double modal_mass = phi.dot(mass.asDiagonal() * phi);
        const double lambda = std::max(0.0, solver.eigenvalues()[mode]);  // the rigid mode: 0
        Mat m;
        m.id = "mode" + std::to_string(mode + 1), m.kind = MatKind::Oscillator, m.rate = "audio";
        m.mass = modal_mass, m.stiffness = lambda * modal_mass,
        m.damping = 2.0 * (losses.sigma0 + losses.sigma1 * lambda) * modal_mass;
        m.display = {{40.0 * (mode + 1), 120.0}};
        modes.push_back(m);
        for (int i = 0; i < n; ++i) shapes[i].push_back(phi[i]);
    }
    // Every mass of the chain has its point, so the string's shape can be drawn; the step
    // moves only those something reads (the ends' links, the bow): the others are summed from
    // the modes when asked (CompiledLevel::derived_points).
    for (int i = 1; i <= n; ++i) {
        Mat p;
        p.id = mass_id(i), p.kind = MatKind::ModalPoint, p.rate = "audio";
        for (int mode = 0; mode < n; ++mode) p.modes.push_back("mode" + std::to_string(mode + 1));
        p.weights = shapes[i - 1];
        p.display = {{40.0 * i, 0.0}};
        points.push_back(p);
    }
    // A bow with a width touches the string through a point of its own, before the bowed
    // point (bow_contact.hpp): the bowed point keeps its shape, so the bow can move on.
    if (wide_bow && bowed > 1 && bowed < n) {
        Mat contact = points[bowed - 1];
        contact.id = kBowContact;
        contact.weights = contact_weights(points[bowed - 2], points[bowed - 1], points[bowed]);
        contact.display = {{40.0 * bowed, -30.0}};
        points.insert(points.begin() + (bowed - 1), contact);
    }
    // The bridge first, then the modes and points in place of s1..sN, then whatever follows
    // (the nut, a body); the inner links go, the end links k0 and kN stay.
    const StringElements chain = string_elements(n);
    std::vector<Mat> mats;
    for (const auto& m : model.mats) {
        const bool in_chain =
            std::find(chain.masses.begin(), chain.masses.end(), m.id) != chain.masses.end();
        if (m.id == mass_id(1)) {
            mats.insert(mats.end(), modes.begin(), modes.end());
            mats.insert(mats.end(), points.begin(), points.end());
        }
        if (!in_chain) mats.push_back(m);
    }
    std::vector<Lia> lias;
    for (const auto& l : model.lias)
        if (l.id == "k0" || l.id == "k" + std::to_string(n) ||
            std::find(chain.links.begin(), chain.links.end(), l.id) == chain.links.end())
            lias.push_back(l);
    model.mats = mats;
    model.lias = lias;
}

}  // namespace archet
