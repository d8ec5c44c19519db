#pragma once
// Reads the signature of bowing from the slip velocity (bow minus string at the bowing
// point): when the bow slips, how often, and for what share of the period. Helmholtz motion
// is one stick and one slip per period of the string's first mode, the slip lasting about β
// of the period (physics.md §4).

#include <vector>

namespace archet {

struct BowingAnalysis {
    int slips = 0;                ///< slip onsets in the window
    double periods = 0;           ///< window length in periods of the nominal pitch
    double slips_per_period = 0;  ///< 1 for Helmholtz motion
    double period = 0;            ///< s, mean time between slip onsets
    double period_spread = 0;     ///< (max − min) / mean of those intervals
    double pitch_cents = 0;       ///< 1/period against the nominal pitch
    double slip_share = 0;        ///< fraction of time slipping
    bool helmholtz() const;       ///< one slip per period, steady, near the pitch
};

/// One slip of the bow on the string: when it started and when it ended (s); `end` is −1
/// while it lasts.
struct Slip {
    double onset = 0, end = -1;
    bool ended() const { return end >= onset; }
    /// Whether the bow slid through half or more of the period this slip begins, up to the
    /// next slip's `next_onset`: Helmholtz motion bowed at β slips for β of it, a bow with too
    /// little force can slip once a period and grip only briefly.
    bool slid_through(double next_onset) const {
        return !ended() || end - onset >= 0.5 * (next_onset - onset);
    }
};

/// Finds where the slip velocity rises through `threshold` (m/s), one sample at a time:
/// the times the bow starts to slip, interpolated between samples, and the times it grips
/// again (the first sample under the threshold).
class SlipDetector {
  public:
    explicit SlipDetector(double sample_rate, double threshold = 1e-3)
        : fs_(sample_rate), threshold_(threshold) {}
    /// Sample i's slip velocity; true when a slip starts at it (its time is then onset()).
    bool add(std::size_t i, double slip_velocity);
    /// True when the slip under way ended at the last sample added (its time is then end()).
    bool ended() const { return ended_; }
    double onset() const { return onset_; }  ///< s
    double end() const { return end_; }      ///< s
    bool slipping() const { return slipping_; }

  private:
    double fs_, threshold_;
    double previous_ = 0, onset_ = 0, end_ = 0;
    bool slipping_ = false, started_ = false, ended_ = false;
};

/// The slips that start in samples [first, last), with their ends (−1: still slipping at
/// `last`); `slipping`, if given, counts the samples of [first, last) that slip.
std::vector<Slip> slips_in(const std::vector<double>& slip_velocity, double sample_rate,
                           std::size_t first, std::size_t last, double threshold = 1e-3,
                           std::size_t* slipping = nullptr);

/// `slip_velocity` sampled at `sample_rate`; analyses samples [first, last). A sample counts
/// as slipping when |v| exceeds `threshold` (m/s).
BowingAnalysis analyse_bowing(const std::vector<double>& slip_velocity, double sample_rate,
                              double pitch, std::size_t first, std::size_t last,
                              double threshold = 1e-3);

/// The attack of a stroke (the paper's Fig. 2): from the bow's first contact to the slip
/// after which every period holds exactly one slip, shorter than half of it, each interval
/// within `tolerance` of the steady period, until the bow lifts (at least `settle` periods).
struct AttackAnalysis {
    double contact = -1;    ///< s, first sample with normal force
    double helmholtz = -1;  ///< s, start of steady Helmholtz motion (−1: never)
    double period = 0;      ///< s, the steady period reached
    bool reached() const { return helmholtz >= 0; }
    double attack() const { return helmholtz - contact; }  ///< s
};

AttackAnalysis analyse_attack(const std::vector<double>& slip_velocity,
                              const std::vector<double>& normal_force, double sample_rate,
                              double pitch, int settle = 10, double tolerance = 0.01,
                              double threshold = 1e-3);

}  // namespace archet
