// A simulation that stops being finite is never heard or written as sound: renders stop at the
// first non-finite sample, naming the time and the element that blew up, and nothing of the
// non-finite block reaches the sink (libsndfile would write NaN as full-scale DC).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/physics/blow_up.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/renderer.hpp"
#include "archet/physics/simulation.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// Renders until it throws; returns the message and checks that the sink saw only finite audio.
std::string render_until_blow_up(Simulation& sim, std::uint64_t frames, std::size_t* sunk) {
    RenderOptions options;
    options.frames = frames;
    options.with_probes = true;
    options.block_frames = 256;
    *sunk = 0;
    try {
        render(sim, options, [&](const RenderBlock& b) {
            for (std::size_t i = 0; i < b.frames; ++i) {
                EXPECT_TRUE(std::isfinite(b.audio[i])) << "at sample " << b.first_frame + i;
                for (std::size_t p = 0; p < b.probe_count; ++p)
                    EXPECT_TRUE(std::isfinite(b.probes[i * b.probe_count + p]));
            }
            *sunk += b.frames;
        });
    } catch (const InputError& e) {
        return e.what();
    }
    return {};
}

TEST(NonFinite, ANanPositionStopsTheRenderNamingTheMass) {
    // Compiled without validation, as a corrupted state or a future bug would leave it.
    Model model = build_bowed_string(test::paper_string_options());
    model.find_mat("s12")->position = std::numeric_limits<double>::quiet_NaN();
    Simulation sim(compile(model));
    std::size_t sunk = 0;
    const std::string message = render_until_blow_up(sim, 48000, &sunk);
    EXPECT_NE(message.find("stopped being finite at t = "), std::string::npos) << message;
    EXPECT_NE(message.find("mass \"s1"), std::string::npos) << message;
    EXPECT_NE(message.find("nothing was written"), std::string::npos) << message;
    EXPECT_LT(sunk, 48000u);
}

TEST(NonFinite, AHugeVelocityOverflowsTheEnergyAndStopsTheRender) {
    // 1e300 m/s: the energy (m·v²/2) is infinite from the first sample.
    Model model = build_bowed_string(test::paper_string_options());
    model.find_mat("s5")->velocity = 1e300;
    Simulation sim(compile(model));
    std::size_t sunk = 0;
    const std::string message = render_until_blow_up(sim, 4800, &sunk);
    EXPECT_NE(message.find("stopped being finite at t = "), std::string::npos) << message;
    EXPECT_EQ(sunk, 0u) << "the first block is already non-finite";
}

TEST(NonFinite, AFiniteRenderRunsToTheEndAndIsReportedFinite) {
    Simulation sim(compile(build_bowed_string(test::paper_string_options())));
    std::size_t sunk = 0;
    EXPECT_EQ(render_until_blow_up(sim, 4800, &sunk), "");
    EXPECT_EQ(sunk, 4800u);
    EXPECT_TRUE(simulation_is_finite(sim));
    EXPECT_FALSE(find_blown_up_element(sim));
}

TEST(NonFinite, TheBlownUpElementIsNamedByItsId) {
    Model model = build_bowed_string(test::paper_string_options());
    model.find_mat("s7")->position = std::numeric_limits<double>::infinity();
    Simulation sim(compile(model));
    const auto element = find_blown_up_element(sim);
    ASSERT_TRUE(element);
    EXPECT_EQ(*element, "mass \"s7\" (position inf)");
    EXPECT_FALSE(simulation_is_finite(sim));
}

TEST(NonFinite, TheMassStoredLastIsCheckedToo) {
    // The bow's surface, stored after the string: it feeds neither the output nor a probe, so
    // only this check can find it.
    Model model = build_bowed_string(test::paper_string_options());
    const CompiledModel compiled = compile(model);
    const CompiledLevel& audio = compiled.levels[0];
    const std::string last = model.mats[audio.element_of[audio.size]].id;
    model.find_mat(last)->position = std::numeric_limits<double>::infinity();
    Simulation sim(compile(model));
    const auto element = find_blown_up_element(sim);
    ASSERT_TRUE(element) << last << " was not checked";
    EXPECT_EQ(*element, "mass " + quoted_text(last) + " (position inf)");
}

}  // namespace
}  // namespace archet
