// The modal string: one damped oscillator per mode of the free chain, modal points at its
// ends and the bowing point. Its partials are the chaplet's, and bowed with the same gesture
// it plays the same sound to round-off.

#include <gtest/gtest.h>

#include <cmath>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// The full string (body, losses, hair-wide bow) or the paper's 60-mass chaplet.
Model build(Tuning tuning, Structure structure, double pitch = 220, bool paper = false) {
    BowedStringOptions o;
    o.pitch = pitch, o.tuning = tuning, o.structure = structure, o.paper = paper;
    return build_bowed_string(o);
}

class ModalString : public ::testing::TestWithParam<Tuning> {};

TEST_P(ModalString, PartialsMatchTheChapletsWithinACent) {
    const ModalAnalysis chain = analyse_modes(build(GetParam(), Structure::Chain));
    const ModalAnalysis modal = analyse_modes(build(GetParam(), Structure::Modal));
    ASSERT_EQ(chain.modes.size(), modal.modes.size());
    int compared = 0;
    for (std::size_t i = 0; i < chain.modes.size(); ++i) {
        EXPECT_EQ(chain.modes[i].partial, modal.modes[i].partial);
        EXPECT_NEAR(1200 * std::log2(modal.modes[i].frequency / chain.modes[i].frequency), 0.0,
                    1e-6);
        EXPECT_NEAR(modal.modes[i].t60 / chain.modes[i].t60, 1.0, 1e-6);
        compared += chain.modes[i].partial >= 1 && chain.modes[i].partial <= 10;
    }
    EXPECT_EQ(compared, 10);
}

TEST_P(ModalString, PlaysTheSameAsTheChaplet) {
    const Model chain_model = build(GetParam(), Structure::Chain);
    Model modal_model = build(GetParam(), Structure::Modal);
    // Each found its own stroke and gain; play both with the chain's.
    modal_model.gesture = chain_model.gesture, modal_model.output_gain = chain_model.output_gain;
    Simulation chain(compile(chain_model));
    Simulation modal(compile(modal_model));
    ASSERT_EQ(chain.probe_count(), modal.probe_count());
    double difference = 0, scale = 0;
    for (int i = 0; i < 48000; ++i) {
        chain.step(), modal.step();
        for (std::size_t p = 0; p < chain.probe_count(); ++p) {
            difference = std::max(difference, std::abs(chain.probe(p) - modal.probe(p)) /
                                                  (std::abs(chain.probe(p)) + 1e-3));
        }
        scale = std::max(scale, std::abs(chain.output()));
    }
    EXPECT_GT(scale, 0.05) << "it was bowed";
    EXPECT_LT(difference, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Tunings, ModalString,
                         ::testing::Values(Tuning::Homogeneous, Tuning::Harmonic));

TEST(ModalString, FileRoundTripsAndNamesItsParts) {
    const Model model = build(Tuning::Homogeneous, Structure::Modal, 220, true);
    EXPECT_EQ(model.name, "bowed-string-220-modal-paper");
    const std::string text = format_model(model);
    EXPECT_EQ(format_model(parse_model(text)), text);
    const Mat* point = model.find_mat("s7");
    ASSERT_NE(point, nullptr);
    EXPECT_EQ(point->kind, MatKind::ModalPoint);
    EXPECT_EQ(point->modes.size(), 60u);
    EXPECT_NE(text.find("\"type\": \"modal_point\""), std::string::npos);
}

TEST(ModalString, ValidationNamesABadModalPoint) {
    const Model good = build(Tuning::Homogeneous, Structure::Modal, 220, true);
    auto refused = [&](auto change, const std::string& expected) {
        Model m = good;
        change(*m.find_mat("s7"));
        try {
            validate_model(m);
            ADD_FAILURE() << "accepted: " << expected;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    };
    refused([](Mat& p) { p.weights.pop_back(); }, "mass \"s7\": has 60 modes but 59 weights");
    refused([](Mat& p) { p.modes[3] = "surface"; }, "mode \"surface\" is a fixed");
    refused([](Mat& p) { p.modes[3] = "nowhere"; }, "mode \"nowhere\" is not a mass of this model");
    refused([](Mat& p) { p.modes.clear(), p.weights.clear(); }, "at least one mode");
}

}  // namespace
}  // namespace archet
