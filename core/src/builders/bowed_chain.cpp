#include "archet/builders/bowed_chain.hpp"

#include <algorithm>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"

namespace archet {

Model build_bowed_chain(int n) {
    if (n < 4 || n > 10'000'000) throw InputError("--chain", "must be 4 to 10000000 masses");
    const double fs = 48000.0, dt = 1.0 / fs;
    const double m = 1e-4;
    const double k = 0.25 * m / (dt * dt);  // normalised K = 0.25: highest mode at λ = 1
    Model model;
    model.name = "bowed-chain-" + std::to_string(n);
    model.description = "Benchmark: bowed chain of " + std::to_string(n) + " masses";
    model.rates = {{"audio", 1}, {"haptic", 16}};
    auto mat = [](std::string id, MatKind kind, std::string rate, double mass) {
        Mat x;
        x.id = std::move(id), x.kind = kind, x.rate = std::move(rate), x.mass = mass;
        return x;
    };
    model.mats.reserve(n + 7);
    model.lias.reserve(n + 4);
    model.mats.push_back(mat("end_a", MatKind::Fixed, "audio", 0));
    for (int i = 1; i <= n; ++i)
        model.mats.push_back(mat("m" + std::to_string(i), MatKind::Mass, "audio", m));
    model.mats.push_back(mat("end_b", MatKind::Fixed, "audio", 0));
    for (int i = 0; i <= n; ++i) {
        Lia l;
        l.id = "l" + std::to_string(i), l.kind = LiaKind::SpringDamper, l.rate = "audio";
        l.from = i == 0 ? "end_a" : "m" + std::to_string(i);
        l.to = i == n ? "end_b" : "m" + std::to_string(i + 1);
        l.stiffness = k, l.damping = 1e-4 * k * dt;
        model.lias.push_back(l);
    }
    const std::string bowed = "m" + std::to_string(std::max(1, n / 10));
    add_bow_module(model, BowedStringOptions{}, bowed);
    model.outputs = {{bowed, Output::Signal::Velocity, 1.0}};
    model.gesture = steady_bow_gesture(0.1, 0.0015, 10.0);
    return model;
}

}  // namespace archet
