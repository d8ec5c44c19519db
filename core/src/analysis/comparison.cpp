#include "archet/analysis/comparison.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include "archet/analysis/shared_first_modes.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

namespace {

// What stops a variant under way: the caller's cancel, or another variant's failure.
struct StopFlags {
    const std::atomic<bool>* cancel = nullptr;
    const std::atomic<bool>* failed = nullptr;
    bool any() const { return (cancel && cancel->load()) || (failed && failed->load()); }
};

// compare_variant(), or nothing once `stop` says so (looked at every few thousand samples).
// `first_modes` is shared by the variants of one comparison.
std::optional<ComparisonRun> render_variant(const Model& model, const Gesture& gesture,
                                            const std::string& parameter, double value,
                                            double seconds, SharedFirstModes& first_modes,
                                            StopFlags stop) {
    Model variant = model;
    set_variant_parameter(variant, parameter, value);
    validate_model(variant);
    const Lia* bow = first_bow(variant);
    if (!bow) throw InputError(variant.name, "has no bow module to compare bowing with");

    ComparisonRun run;
    std::ostringstream label;
    label << parameter << "=" << value;
    run.label = label.str();
    run.value = value;
    try {
        run.fundamental = first_modes.of(variant).frequency;
    } catch (const std::exception&) {
        run.fundamental = 0;  // no linear part to analyse: no per-period figure
    }
    Simulation sim(compile(variant));
    const Gesture stroke = gesture;  // its own: reading a gesture moves the cursor it keeps
    sim.set_gesture_track(&stroke);
    sim.enable_accounting(true);
    run.sample_rate = sim.sample_rate();
    const MatSlot bowed = sim.model().mat_slots.at(bow->bowed_string());
    const auto frames = static_cast<std::size_t>(seconds * sim.sample_rate());
    std::vector<int> links;
    for (const auto& id : string_links(variant))
        links.push_back(static_cast<int>(variant.find_lia(id) - variant.lias.data()));
    auto string_dissipation = [&] {
        double total = 0;
        for (int l : links) total += sim.dissipated_by_element()[static_cast<std::size_t>(l)];
        return total;
    };
    const DenormalGuard no_denormals;
    // By the string, up to each sample from half-way, where the steady part is looked for (a sum
    // over its links: not kept where nothing reads it).
    const std::size_t from = frames / 2;
    std::vector<double> dissipated(frames + 1, 0.0);
    std::size_t last_contact = 0;
    constexpr std::size_t kStopLooks = 4096;  // samples between two looks at `stop`
    for (std::size_t i = 0; i < frames; ++i) {
        if (i % kStopLooks == 0 && stop.any()) return std::nullopt;
        sim.step();
        run.audio.push_back(sim.output());
        run.bow_force.push_back(sim.model().bows[0].friction);
        run.displacement.push_back(sim.position(bowed));
        if (i + 1 >= from) dissipated[i + 1] = string_dissipation();
        if (sim.model().bows[0].normal > 0) last_contact = i;
    }
    // Steady bowing: from half-way to shortly before the bow leaves (a lift ends most
    // gestures, and the free decay after it is not what is compared).
    const auto margin = static_cast<std::size_t>(0.05 * sim.sample_rate());
    run.steady_end = last_contact > margin ? last_contact - margin : frames;
    if (run.steady_end > from && run.fundamental > 0) {
        const double periods =
            static_cast<double>(run.steady_end - from) / sim.sample_rate() * run.fundamental;
        run.dissipated_per_period = (dissipated[run.steady_end] - dissipated[from]) / periods;
    }
    return run;
}

}  // namespace

ComparisonRun compare_variant(const Model& model, const Gesture& gesture,
                              const std::string& parameter, double value, double seconds) {
    SharedFirstModes first_modes;
    return *render_variant(model, gesture, parameter, value, seconds, first_modes, {});
}

ComparedVariants compare_variants(const Model& model, const Gesture& gesture,
                                  const std::string& parameter, const std::vector<double>& values,
                                  double seconds, int jobs, const std::atomic<bool>* cancel,
                                  const std::function<void(std::size_t, std::size_t)>& progress) {
    std::vector<std::optional<ComparisonRun>> runs(values.size());
    std::vector<std::exception_ptr> errors(values.size());
    std::atomic<bool> failed{false};  // a variant threw: no other starts, those under way stop
    std::exception_ptr thrown;        // what kept the threads from running, if anything
    SharedFirstModes first_modes;     // a bow's or a hand's variants share their string's
    try {
        parallel_for(
            values.size(), jobs,
            [&](std::size_t i) {
                try {
                    runs[i] = render_variant(model, gesture, parameter, values[i], seconds,
                                             first_modes, {cancel, &failed});
                } catch (...) {
                    errors[i] = std::current_exception();
                    failed = true;
                    throw;
                }
            },
            cancel, progress);
    } catch (...) {
        thrown = std::current_exception();
    }
    // The runs up to the first that did not finish. It threw, or was stopped: by the caller's
    // cancel, else by a failure (the first in the order of the values is the one reported).
    const auto failure = std::find_if(errors.begin(), errors.end(), [](auto& e) { return !!e; });
    const std::exception_ptr first_error = failure != errors.end() ? *failure : thrown;
    ComparedVariants compared;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!runs[i]) {
            compared.error = errors[i]                    ? errors[i]
                             : (cancel && cancel->load()) ? nullptr
                                                          : first_error;
            compared.cancelled = !compared.error;
            break;
        }
        compared.runs.push_back(std::move(*runs[i]));
    }
    return compared;
}

}  // namespace archet
