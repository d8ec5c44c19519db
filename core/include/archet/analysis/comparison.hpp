#pragma once
// One gesture played on variants of a model, as in the paper's Fig. 5: for each, the sound,
// the bow force and the displacement at the bowing point, and the energy the string's links
// dissipate per period of its first mode. Offline and deterministic.

#include <atomic>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"

namespace archet {

struct ComparisonRun {
    std::string label;  ///< "string.damping=0.01"
    double value = 0;
    double sample_rate = 48000;
    double fundamental = 0;            ///< Hz, first mode of the variant
    std::vector<double> audio;         ///< the model's output
    std::vector<double> bow_force;     ///< N, friction on the string
    std::vector<double> displacement;  ///< m, of the bowed string mass
    /// The last sample of steady bowing: 50 ms before the bow leaves the string (or the end).
    std::size_t steady_end = 0;
    /// J per period of f1 dissipated by the string's links, from half-way to steady_end.
    double dissipated_per_period = 0;
};

/// Renders `gesture` on `model` with `parameter` (see set_variant_parameter) at `value`, for
/// `seconds`. Throws InputError for a bad parameter or a variant that does not validate.
ComparisonRun compare_variant(const Model& model, const Gesture& gesture,
                              const std::string& parameter, double value, double seconds);

/// The variants of a comparison, in the order of their values: those before the first that
/// did not finish, and why it did not (`error`, what it threw; else it was cancelled).
struct ComparedVariants {
    std::vector<ComparisonRun> runs;
    std::exception_ptr error;
    bool cancelled = false;
    bool complete() const { return !error && !cancelled; }
};

/// compare_variant() for each of `values`, on `jobs` threads: each variant is independent, so
/// the runs are the same on any number of threads. `progress(done, total)` is called from the
/// caller's thread about ten times a second. Once `*cancel` is set, or a variant throws, no
/// other starts and those under way stop within a few thousand samples.
ComparedVariants compare_variants(
    const Model& model, const Gesture& gesture, const std::string& parameter,
    const std::vector<double>& values, double seconds, int jobs,
    const std::atomic<bool>* cancel = nullptr,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace archet
