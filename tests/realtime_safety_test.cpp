// step() runs on the real-time threads later: it must never allocate. Counts every
// operator new in this process while a bowed string plays.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

#include "archet/bowed_string.hpp"
#include "archet/compiled_model.hpp"
#include "archet/simulation.hpp"

namespace {
std::atomic<long> allocations{0};
std::atomic<bool> counting{false};
}  // namespace

void* operator new(std::size_t size) {
    if (counting.load(std::memory_order_relaxed))
        allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

namespace archet {
namespace {

TEST(RealtimeSafety, StepProbesAndOutputNeverAllocate) {
    BowedStringOptions o;
    Model model = build_bowed_string(o);
    Control c;
    c.id = "c", c.target_element = "friction", c.target_parameter = "mu_s",
    c.source = Control::Source::Envelope;
    c.envelope = {{0, 0.8}, {1, 0.9}}, c.minimum = 0.5, c.maximum = 1.0;
    model.controls.push_back(c);
    Simulation sim(compile(model));
    sim.enable_accounting(true);
    const auto mu_d =
        sim.model().resolve_parameter("friction", "mu_d");  // resolved off the real-time path
    double sink = 0;
    counting = true;
    for (int i = 0; i < 48000; ++i) {
        sim.step();
        sink += sim.output();
        for (std::size_t p = 0; p < sim.probe_count(); ++p) sink += sim.probe(p);
    }
    sim.set_parameter(mu_d, 0.25);
    counting = false;
    EXPECT_EQ(allocations.load(), 0);
    EXPECT_TRUE(std::isfinite(sink));
    // The counter works: an allocation outside is seen.
    counting = true;
    auto* p = new int(3);
    counting = false;
    delete p;
    EXPECT_EQ(allocations.load(), 1);
}

}  // namespace
}  // namespace archet
