#include "archet/analysis/bowing_analysis.hpp"

#include <algorithm>
#include <cmath>

namespace archet {

bool BowingAnalysis::helmholtz() const {
    return std::abs(slips_per_period - 1.0) < 0.05 && period_spread < 0.1 &&
           std::abs(pitch_cents) < 50.0 && slip_share > 0.0 && slip_share < 0.5;
}

bool SlipDetector::add(std::size_t i, double v) {
    const double a1 = std::abs(v);
    const bool slip = a1 > threshold_;
    const bool starts = slip && !slipping_ && started_;
    if (starts) {
        const double a0 = previous_;
        const double fraction = a1 > a0 ? (threshold_ - a0) / (a1 - a0) : 0.0;
        onset_ = (static_cast<double>(i - 1) + std::clamp(fraction, 0.0, 1.0)) / fs_;
    }
    ended_ = slipping_ && !slip;
    if (ended_) end_ = static_cast<double>(i) / fs_;
    slipping_ = slip, previous_ = a1, started_ = true;
    return starts;
}

std::vector<Slip> slips_in(const std::vector<double>& v, double fs, std::size_t first,
                           std::size_t last, double threshold, std::size_t* slipping) {
    std::vector<Slip> slips;
    std::size_t count = 0;
    SlipDetector detector(fs, threshold);
    for (std::size_t i = first; i < std::min(last, v.size()); ++i) {
        if (detector.add(i, v[i])) slips.push_back({detector.onset()});
        if (detector.ended() && !slips.empty()) slips.back().end = detector.end();
        count += detector.slipping();
    }
    if (slipping) *slipping = count;
    return slips;
}

AttackAnalysis analyse_attack(const std::vector<double>& v, const std::vector<double>& normal,
                              double fs, double pitch, int settle, double tolerance,
                              double threshold) {
    AttackAnalysis a;
    std::size_t end = std::min(v.size(), normal.size());
    std::size_t contact = 0;
    while (contact < end && !(normal[contact] > 0.0)) ++contact;
    if (contact >= end) return a;
    a.contact = static_cast<double>(contact) / fs;
    while (end > contact && !(normal[end - 1] > 0.0)) --end;  // up to the bow's last contact
    const std::vector<Slip> slips = slips_in(v, fs, contact, end, threshold);
    if (slips.size() < static_cast<std::size_t>(2 * settle) + 1) return a;
    auto interval = [&](std::size_t i) { return slips[i + 1].onset - slips[i].onset; };
    // The steady period: the median interval over the second half of the contact, which
    // outvotes the lift at its end.
    std::vector<double> later;
    for (std::size_t i = slips.size() / 2; i + 1 < slips.size(); ++i) later.push_back(interval(i));
    std::nth_element(later.begin(), later.begin() + later.size() / 2, later.end());
    const double period = later[later.size() / 2];
    if (std::abs(std::log2(period * pitch)) > 0.1) return a;  // not near the pitch: no Helmholtz
    // Stick and slip change on samples: allow a sample and a half of jitter at high pitches.
    const double allowed = std::max(tolerance * period, 1.5 / fs);
    // Steady Helmholtz motion starts after the last irregular period before the bow lifts
    // (the last 50 ms of contact are the lift and do not count).
    const double lift = static_cast<double>(end) / fs - 0.05;
    std::size_t last_good = 0;  // slips [start, last_good] are one a period apart
    while (last_good + 1 < slips.size() && slips[last_good + 1].onset <= lift) ++last_good;
    auto steady = [&](std::size_t i) {
        return std::abs(interval(i) - period) <= allowed &&
               !slips[i].slid_through(slips[i + 1].onset);
    };
    std::size_t start = last_good;
    while (start > 0 && steady(start - 1)) --start;
    if (last_good - start < static_cast<std::size_t>(settle)) return a;
    a.helmholtz = slips[start].onset;
    a.period = period;
    return a;
}

BowingAnalysis analyse_bowing(const std::vector<double>& v, double fs, double pitch,
                              std::size_t first, std::size_t last, double threshold) {
    BowingAnalysis a;
    last = std::min(last, v.size());
    if (last <= first + 1) return a;
    std::size_t slipping = 0;
    const std::vector<Slip> slips = slips_in(v, fs, first, last, threshold, &slipping);
    a.slips = static_cast<int>(slips.size());
    a.periods = static_cast<double>(last - first) / fs * pitch;
    a.slips_per_period = a.slips / a.periods;
    a.slip_share = static_cast<double>(slipping) / static_cast<double>(last - first);
    if (slips.size() >= 3) {
        std::vector<double> intervals;
        for (std::size_t i = 1; i < slips.size(); ++i)
            intervals.push_back(slips[i].onset - slips[i - 1].onset);
        a.period =
            (slips.back().onset - slips.front().onset) / static_cast<double>(intervals.size());
        const auto [lo, hi] = std::minmax_element(intervals.begin(), intervals.end());
        a.period_spread = (*hi - *lo) / a.period;
        a.pitch_cents = 1200.0 * std::log2(1.0 / (a.period * pitch));
    }
    return a;
}

}  // namespace archet
