#include "archet/physics/uniform_span.hpp"

#include <algorithm>
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

UniformSpan::UniformSpan(int first, int last, const ChainCoefficients& shared)
    : first(first), last(last), shared(shared) {
    std::fill_n(lanes.k, 8, shared.k), std::fill_n(lanes.zdt, 8, shared.zdt);
    std::fill_n(lanes.length, 8, shared.length), std::fill_n(lanes.c, 8, shared.c);
    std::fill_n(lanes.a, 8, shared.a), std::fill_n(lanes.b, 8, shared.b);
    std::fill_n(lanes.e, 8, shared.e);
    for (int i = 0; i < 3; ++i) rounds_[i] = shared_rounds(first, last, 2 << i);
}

UniformSpan UniformSpan::part(int part_first, int part_last) const {
    return UniformSpan(part_first, part_last, shared);
}

bool ChainCoefficients::operator==(const ChainCoefficients& o) const {
    return same_bits(c, o.c) && same_bits(mass, o.mass) && same_bits(k, o.k) &&
           same_bits(zdt, o.zdt) && same_bits(length, o.length) &&
           same_bits(ground_k, o.ground_k) && same_bits(ground_zdt, o.ground_zdt) &&
           same_bits(rest, o.rest) && same_bits(a, o.a) && same_bits(b, o.b) && same_bits(e, o.e);
}

void UniformRuns::remove(int i) {
    std::copy(run_.begin() + i + 1, run_.begin() + count_, run_.begin() + i);
    --count_;
}

void UniformRuns::keep(const UniformSpan& run) {
    if (run.length() < kShortest) return;
    if (count_ == kCapacity) {
        int shortest = 0;
        for (int i = 1; i < count_; ++i)
            if (run_[i].length() <= run_[shortest].length()) shortest = i;
        if (run.length() <= run_[shortest].length()) return;
        remove(shortest);
    }
    run_[count_++] = run;
}

void UniformRuns::split(int i, int s) {
    const UniformSpan left = run_[i].part(run_[i].first, s - 1);
    const UniformSpan right = run_[i].part(s + 1, run_[i].last);
    const bool keep_left = left.length() >= kShortest, keep_right = right.length() >= kShortest;
    if (keep_left && keep_right && count_ < kCapacity) {
        std::copy_backward(run_.begin() + i + 1, run_.begin() + count_, run_.begin() + count_ + 1);
        ++count_;
        run_[i] = left, run_[i + 1] = right;
    } else if (keep_left || keep_right) {
        run_[i] = keep_left && (!keep_right || left.length() >= right.length()) ? left : right;
    } else {
        remove(i);
    }
}

void find_uniform_runs(CompiledLevel& lv) {
    lv.uniform.clear();
    // Short runs are not kept: not worth filling their lanes (a model swap does this on the
    // real-time thread).
    auto keep = [&](int first, int last) {
        if (last - first + 1 >= UniformRuns::kShortest)
            lv.uniform.keep(UniformSpan(first, last, chain_coefficients(lv, first)));
    };
    // The unlinked runs are left out: the chain loop moves their MATs by their own update.
    // Over the chain loop's MATs alone: it stops before the held ones at the end.
    const int last_moving = lv.size - lv.fixed_after;
    auto unlinked = lv.unlinked.begin();
    int start = 1;
    for (int s = 1; s <= last_moving; ++s) {
        if (unlinked != lv.unlinked.end() && s == unlinked->first) {  // (the run before ended)
            s = unlinked->last, start = s + 1;
            ++unlinked;
            continue;
        }
        const bool run_ends = s == last_moving ||
                              (unlinked != lv.unlinked.end() && s + 1 == unlinked->first) ||
                              !(chain_coefficients(lv, s + 1) == chain_coefficients(lv, start));
        if (!run_ends) continue;
        keep(start, s);
        start = s + 1;
    }
}

void split_uniform_run(CompiledLevel& lv, int s) {
    const UniformRuns& runs = lv.uniform;
    int i = 0;
    while (i < runs.count() && runs[i].last < s) ++i;
    if (i < runs.count() && runs[i].first <= s && !(chain_coefficients(lv, s) == runs[i].shared))
        lv.uniform.split(i, s);
}

}  // namespace archet
