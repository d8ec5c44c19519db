#include "archet/physics/unlinked_runs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"

namespace archet {

namespace {

// Chain link j (joining storage j and j + 1) stands for no element and moves nothing; on a
// level that knows its links (knows_its_links()).
bool absent_link(const CompiledLevel& lv, int j) {
    return lv.chain_element[j] < 0 && lv.chain_k[j] == 0.0 && lv.chain_zdt[j] == 0.0 &&
           lv.chain_length[j] == 0.0;
}

// A level built without elements behind its chain (a test's) has no unlinked MATs: its links
// are taken as they are.
bool knows_its_links(const CompiledLevel& lv) {
    return static_cast<int>(lv.chain_element.size()) >= lv.size + 1;
}

int zero_prone_rests(const CompiledLevel& lv, const UnlinkedRun& run) {
    int count = 0;
    for (int s = run.first; s <= run.last; ++s) count += may_leave_negative_zero(lv.update_rest[s]);
    return count;
}

}  // namespace

std::vector<UnlinkedRun> find_unlinked_runs(const CompiledLevel& lv) {
    std::vector<UnlinkedRun> runs;
    if (!knows_its_links(lv) || !grounds_in_chain_loop(lv)) return runs;
    const int last_moving = lv.size - lv.fixed_after;
    int first = 0;  // of the run being found, 0 for none
    for (int s = 1; s <= last_moving + 1; ++s) {
        const bool unlinked = s <= last_moving && absent_link(lv, s - 1) && absent_link(lv, s);
        if (unlinked && first == 0) first = s;
        if (unlinked || first == 0) continue;
        if (s - first >= UnlinkedRun::kShortest) {
            UnlinkedRun run{.first = first, .last = s - 1};
            run.zero_prone_rests = zero_prone_rests(lv, run);
            runs.push_back(run);
        }
        first = 0;
    }
    return runs;
}

void recheck_unlinked_runs(CompiledLevel& lv) {
    std::erase_if(lv.unlinked, [&](const UnlinkedRun& run) {
        for (int j = run.first - 1; j <= run.last; ++j)
            if (!absent_link(lv, j)) return true;
        return false;
    });
    for (UnlinkedRun& run : lv.unlinked) run.zero_prone_rests = zero_prone_rests(lv, run);
}

void refolded_unlinked(CompiledLevel& lv, int s, bool was_zero_prone) {
    const auto after =
        std::upper_bound(lv.unlinked.begin(), lv.unlinked.end(), s,
                         [](int s, const UnlinkedRun& run) { return s < run.first; });
    if (after == lv.unlinked.begin()) return;
    UnlinkedRun& run = *std::prev(after);
    if (s <= run.last)
        run.zero_prone_rests += may_leave_negative_zero(lv.update_rest[s]) - was_zero_prone;
}

bool may_leave_negative_zero(double e) {
    // Below 2^−969 in size, a sum with e may fall below the smallest normal (2^−1022): e and
    // its addend are multiples of ulps of at least 2^−1022 above it, a sum of nothing smaller.
    return std::bit_cast<std::uint64_t>(e) != 0 && std::abs(e) < 0x1p-969;
}

}  // namespace archet
