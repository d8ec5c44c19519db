#include "archet/bowing_analysis.hpp"

#include <algorithm>
#include <cmath>

namespace archet {

bool BowingAnalysis::helmholtz() const {
    return std::abs(slips_per_period - 1.0) < 0.05 && period_spread < 0.1 &&
           std::abs(pitch_cents) < 50.0 && slip_share > 0.0 && slip_share < 0.5;
}

BowingAnalysis analyse_bowing(const std::vector<double>& v, double fs, double pitch,
                              std::size_t first, std::size_t last, double threshold) {
    BowingAnalysis a;
    last = std::min(last, v.size());
    if (last <= first + 1) return a;
    std::vector<double> onsets;
    std::size_t slipping = 0;
    bool was_slipping = std::abs(v[first]) > threshold;
    for (std::size_t i = first; i < last; ++i) {
        const bool slip = std::abs(v[i]) > threshold;
        slipping += slip;
        if (slip && !was_slipping && i > first) {
            // Sub-sample onset: where |v| crosses the threshold between the two samples.
            const double a0 = std::abs(v[i - 1]), a1 = std::abs(v[i]);
            const double fraction = a1 > a0 ? (threshold - a0) / (a1 - a0) : 0.0;
            onsets.push_back((static_cast<double>(i - 1) + std::clamp(fraction, 0.0, 1.0)) / fs);
        }
        was_slipping = slip;
    }
    a.slips = static_cast<int>(onsets.size());
    a.periods = static_cast<double>(last - first) / fs * pitch;
    a.slips_per_period = a.slips / a.periods;
    a.slip_share = static_cast<double>(slipping) / static_cast<double>(last - first);
    if (onsets.size() >= 3) {
        std::vector<double> intervals;
        for (std::size_t i = 1; i < onsets.size(); ++i)
            intervals.push_back(onsets[i] - onsets[i - 1]);
        a.period = (onsets.back() - onsets.front()) / static_cast<double>(intervals.size());
        const auto [lo, hi] = std::minmax_element(intervals.begin(), intervals.end());
        a.period_spread = (*hi - *lo) / a.period;
        a.pitch_cents = 1200.0 * std::log2(1.0 / (a.period * pitch));
    }
    return a;
}

}  // namespace archet
