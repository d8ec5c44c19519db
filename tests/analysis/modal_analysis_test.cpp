// Modal analysis against simulation (FFT peaks of a struck string), against the closed form
// of a chain's mode shapes, and on bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <unsupported/Eigen/FFT>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// Frequency of the strongest spectral peak within ±band of `near` (Hz), interpolated on the
// log magnitude of a Hann-windowed FFT.
double peak_near(const std::vector<double>& spectrum_db, double fs, std::size_t fft_size,
                 double near, double band) {
    const double bin_hz = fs / fft_size;
    const auto lo = static_cast<std::size_t>((near - band) / bin_hz),
               hi = static_cast<std::size_t>((near + band) / bin_hz);
    std::size_t best = lo;
    for (std::size_t b = lo; b <= hi; ++b)
        if (spectrum_db[b] > spectrum_db[best]) best = b;
    const double a = spectrum_db[best - 1], c = spectrum_db[best], d = spectrum_db[best + 1];
    return (static_cast<double>(best) + 0.5 * (a - d) / (a - 2 * c + d)) * bin_hz;
}

TEST(ModalAnalysis, PartialsMatchTheFftPeaksOfAStruckString) {
    for (auto tuning : {Tuning::Homogeneous, Tuning::Harmonic}) {
        BowedStringOptions o;
        o.pitch = 220, o.tuning = tuning, o.string_t60 = 30, o.with_gesture = false;
        o.paper = true;  // link damping alone: 30 s at f1
        Model model = build_bowed_string(o);
        model.find_mat("s20")->velocity = 0.05;  // strike; the bow rests without pressing
        const ModalAnalysis modes = analyse_modes(model);
        Simulation sim(compile(model));
        const std::size_t n = 1 << 16;
        std::vector<double> x(n);
        const auto probe = sim.model().mat_slots.at("s7");
        for (std::size_t i = 0; i < n; ++i) sim.step(), x[i] = sim.position(probe);
        for (std::size_t i = 0; i < n; ++i)
            x[i] *= 0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / n);
        Eigen::FFT<double> fft;
        std::vector<std::complex<double>> spectrum;
        fft.fwd(spectrum, x);
        std::vector<double> db(n / 2);
        for (std::size_t b = 0; b < n / 2; ++b)
            db[b] = 20 * std::log10(std::abs(spectrum[b]) + 1e-300);

        int checked = 0;
        for (const auto& mode : modes.modes) {
            if (mode.support || mode.partial > 10) continue;
            const double measured = peak_near(db, 48000, n, mode.frequency, 0.02 * mode.frequency);
            EXPECT_NEAR(1200 * std::log2(measured / mode.frequency), 0.0, 0.5)
                << "partial " << mode.partial << " at " << mode.frequency << " Hz";
            ++checked;
        }
        EXPECT_EQ(checked, 10);
        EXPECT_NEAR(modes.fundamental, 220, 1e-6);
    }
}

TEST(ModalAnalysis, ChainShapesAreSinesAndTheStringIsSeparatedFromItsBridges) {
    const double fs = 48000, dt = 1 / fs, m = 1e-4;
    const int n = 20;
    const Model chain = test::chain(n, m, 0.5 * m / (dt * dt), 1e-3 * m / dt, fs);
    const ModalAnalysis modes = analyse_modes(assemble_linear_system(chain), chain);
    ASSERT_EQ(modes.modes.size(), static_cast<std::size_t>(n));
    for (int k : {1, 3, 10}) {
        const ModeInfo& mode = modes.modes[k - 1];
        EXPECT_EQ(mode.partial, k);
        double dot = 0, norm_a = 0, norm_b = 0;
        for (int i = 1; i <= n; ++i) {
            const double expected = std::sin(i * k * std::numbers::pi / (n + 1));
            const double got = modes.shape_at(mode, "m" + std::to_string(i));
            dot += expected * got, norm_a += expected * expected, norm_b += got * got;
        }
        EXPECT_NEAR(std::abs(dot) / std::sqrt(norm_a * norm_b), 1.0, 1e-9) << "mode " << k;
    }
    BowedStringOptions o;
    o.body = "none", o.with_gesture = false;  // the two bridges
    const ModalAnalysis string = analyse_modes(build_bowed_string(o));
    int supports = 0;
    for (const auto& mode : string.modes) supports += mode.support;
    EXPECT_EQ(supports, 2) << "one mode per bridge";
    EXPECT_EQ(string.modes.size(), string.dofs.size());
}

TEST(ModalAnalysis, RefusesAModelWithNoLinearPart) {
    Model model;
    model.mats = {test::fixed("a"), test::fixed("b")};
    validate_model(model);
    try {
        analyse_modes(model);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("no linear part"), std::string::npos) << e.what();
    }
}

// The level's masses take their DOFs first, in the model's order; a mass of another level
// that a link reaches takes one when the link is met, its "from" end before its "to" end
// (a link's two ends were once looked up in an order the compiler chose).
TEST(LinearSystem, MassesTakeTheirDofsInAnOrderOfTheModels) {
    Model model;
    model.rates = {{"audio", 1}, {"slow", 2}};
    model.mats = {test::fixed("wall"), test::mass("b", 1e-3, 0, "slow"),
                  test::mass("a", 1e-3, 0, "slow"), test::mass("x", 1e-3)};
    model.lias = {test::spring_damper("k1", "x", "wall", 10, 0.1),
                  test::spring_damper("k2", "a", "b", 10, 0.1)};
    const LinearSystem sys = assemble_linear_system(model, "audio");
    EXPECT_EQ(sys.dofs, (std::vector<std::string>{"x", "a", "b"}));
    ASSERT_EQ(sys.size(), 3);
    EXPECT_EQ(sys.stiffness.coeff(1, 2), -10.0) << "k2 joins a and b";
    EXPECT_EQ(sys.stiffness.coeff(0, 0), 10.0) << "k1 holds x to the wall";
    EXPECT_EQ(sys.damping.coeff(2, 2), 0.1);
}

TEST(ModalAnalysis, RefusesASingularMassMatrix) {
    Model model = test::chain(3, 1e-4, 100, 0);
    LinearSystem sys = assemble_linear_system(model);
    sys.mass[1] = 0.0;
    try {
        analyse_modes(sys, model);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("mass \"m2\": the mass matrix is singular"),
                  std::string::npos)
            << e.what();
    }
    // Through the command line the same model file never gets that far: validation names it.
    const auto dir = test::temp_dir("singular");
    auto text = test::read_file(test::resource("models/bowed-string-220-paper.json"));
    const std::string from =
        "\"id\": \"s5\",\n      \"type\": \"mass\",\n      \"rate\": \"audio\",\n      "
        "\"position\": 0.0,\n      \"mass\": ";
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at + from.size(), text.find(',', at + from.size()) - at - from.size(), "0.0");
    { std::ofstream(dir / "m.json") << text; }
    const auto r = test::run_archet({"modes", (dir / "m.json").string()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("mass \"s5\": mass must be above 0 kg (is 0)"), std::string::npos)
        << r.err;
    const auto none = test::run_archet({"modes", test::test_data("no-linear-part.json").string()});
    EXPECT_EQ(none.status, 2);
    EXPECT_NE(none.err.find("no linear part"), std::string::npos) << none.err;
}

TEST(ModalAnalysis, CommandLineReportsPartialsCentsAndShapes) {
    const auto r =
        test::run_archet({"modes", test::resource("models/bowed-string-220-paper.json").string(),
                          "--json", "--limit", "12"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j["fundamental"].get<double>(), 220.0, 1e-6);
    ASSERT_EQ(j["modes"].size(), 12u);
    const auto& tenth = j["modes"][11];  // two bridge modes, then partials 1..10
    EXPECT_EQ(tenth["partial"].get<int>(), 10);
    EXPECT_LT(tenth["cents"].get<double>(), -20.0) << "a homogeneous chaplet's partials go flat";
    EXPECT_TRUE(tenth["shape"].contains("bow_point_x"));
}

}  // namespace
}  // namespace archet
