// The unilateral buffer acts only in contact and only ever pushes.

#include <gtest/gtest.h>

#include <cmath>

#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

Model colliding_pair(double gap, double damping) {
    Model model;
    model.mats = {test::mass("a", 0.01, 0.0), test::mass("b", 0.02, 0.01)};
    model.mats[0].velocity = 1.0;  // a flies towards b
    Lia l;
    l.id = "contact", l.kind = LiaKind::Buffer, l.from = "a", l.to = "b";
    l.stiffness = 1e4, l.damping = damping, l.length = gap;
    model.lias.push_back(l);
    model.probes = {{"fb", ProbeKind::Force, "b"}, {"fa", ProbeKind::Force, "a"}};
    validate_model(model);
    return model;
}

TEST(Buffer, ActsOnlyInContactAndOnlyPushes) {
    for (double gap : {0.0, 0.002}) {
        Simulation sim(compile(colliding_pair(gap, 0.5)));
        const auto a = sim.model().mat_slots.at("a"), b = sim.model().mat_slots.at("b");
        int in_contact = 0;
        for (int i = 0; i < 4800; ++i) {
            const double separation_before = sim.position(b) - sim.position(a);
            sim.step();
            const double force_on_b = sim.probe(0);
            EXPECT_GE(force_on_b, 0.0) << "a buffer never pulls";
            EXPECT_EQ(force_on_b, -sim.probe(1)) << "action equals reaction";
            if (separation_before >= gap)
                EXPECT_EQ(force_on_b, 0.0) << "no force out of contact, step " << i;
            else
                ++in_contact;
        }
        EXPECT_GT(in_contact, 10);
        // After the collision they separate: b moves away faster than a.
        EXPECT_GT(sim.velocity(b), sim.velocity(a));
    }
}

TEST(Buffer, ConservesMomentumThroughTheCollision) {
    Simulation sim(compile(colliding_pair(0.0, 2.0)));
    const auto a = sim.model().mat_slots.at("a"), b = sim.model().mat_slots.at("b");
    const double p0 = 0.01 * 1.0;
    for (int i = 0; i < 4800; ++i) sim.step();
    EXPECT_NEAR(0.01 * sim.velocity(a) + 0.02 * sim.velocity(b), p0, 1e-14);
}

}  // namespace
}  // namespace archet
