#include "archet/physics/uniform_span.hpp"

#include <bit>
#include <cstdint>

#include "archet/physics/compiled_model.hpp"

namespace archet {

namespace {
bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// MAT s's coefficients as the chain loop and the stored energy read them from the arrays.
ChainCoefficients chain_coefficients(const CompiledLevel& lv, int s) {
    return {lv.coeff[s],        lv.mass[s],      lv.chain_k[s],    lv.chain_zdt[s],
            lv.chain_length[s], lv.ground_k[s],  lv.ground_zdt[s], lv.ground_rest[s],
            lv.update_x[s],     lv.update_xp[s], lv.update_rest[s]};
}
}  // namespace

bool ChainCoefficients::operator==(const ChainCoefficients& o) const {
    return same_bits(c, o.c) && same_bits(mass, o.mass) && same_bits(k, o.k) &&
           same_bits(zdt, o.zdt) && same_bits(length, o.length) &&
           same_bits(ground_k, o.ground_k) && same_bits(ground_zdt, o.ground_zdt) &&
           same_bits(rest, o.rest) && same_bits(a, o.a) && same_bits(b, o.b) && same_bits(e, o.e);
}

void find_uniform_span(CompiledLevel& lv) {
    lv.uniform = UniformSpan{};
    int start = 1;
    for (int s = 1; s <= lv.size; ++s) {
        const bool run_ends =
            s == lv.size || !(chain_coefficients(lv, s + 1) == chain_coefficients(lv, start));
        if (!run_ends) continue;
        if (s - start > lv.uniform.last - lv.uniform.first)
            lv.uniform = {start, s, chain_coefficients(lv, start)};
        start = s + 1;
    }
}

void narrow_uniform_span(CompiledLevel& lv, int s) {
    UniformSpan& run = lv.uniform;
    if (s < run.first || s > run.last || chain_coefficients(lv, s) == run.shared) return;
    if (s - run.first >= run.last - s)
        run.last = s - 1;
    else
        run.first = s + 1;
}

}  // namespace archet
