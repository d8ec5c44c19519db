#include "archet/physics/parameter_smoother.hpp"

#include <algorithm>

namespace archet {

void ParameterSmoother::glide(Simulation& sim, const ParameterSlot& slot, double target,
                              int samples) {
    const double from = sim.read_slot(slot);
    for (std::size_t i = 0; i < count_; ++i)
        if (glides_[i].slot == slot) {
            glides_[i] = {slot, from, target, 0, std::max(samples, 1)};
            return;
        }
    if (count_ == kCapacity || samples <= 1) {
        sim.write_slot(slot, target);
        return;
    }
    glides_[count_++] = {slot, from, target, 0, samples};
}

bool ParameterSmoother::resume(const Glide& glide) {
    if (count_ == kCapacity) return false;
    glides_[count_++] = glide;
    return true;
}

void ParameterSmoother::advance(Simulation& sim) {
    if (count_ == 0) return;
    for (std::size_t i = 0; i < count_;) {
        Glide& g = glides_[i];
        ++g.done;
        const double u = static_cast<double>(g.done) / g.total;
        sim.write_slot(g.slot, g.done >= g.total ? g.to : g.from + u * (g.to - g.from));
        if (g.done >= g.total)
            glides_[i] = glides_[--count_];  // finished: drop it
        else
            ++i;
    }
    // The glides split the chain loop's runs of alike MATs; the values they reached may
    // leave the MATs alike again (a knob that moves every damper of a string).
    if (count_ == 0) sim.refresh_uniform_runs();
}

}  // namespace archet
