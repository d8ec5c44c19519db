#include "archet/physics/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "archet/common/denormal_guard.hpp"
#include "archet/physics/blow_up.hpp"
#include "archet/physics/chain_build_choice.hpp"

namespace archet {

namespace {
constexpr std::uint64_t kFramesWorthChoosingABuild = 48000;  ///< the few ms of trials ≪ the render
}  // namespace

void render(Simulation& sim, const RenderOptions& options,
            const std::function<void(const RenderBlock&)>& sink) {
    if (options.block_frames == 0) throw std::invalid_argument("render: block_frames is 0");
    const DenormalGuard no_denormals;
    const std::size_t probe_count = options.with_probes ? sim.probe_count() : 0;
    std::vector<double> audio(options.block_frames);
    std::vector<double> probes(options.block_frames * probe_count);
    // A long render runs the fastest build of the bowed chain's loop here (timed at its start):
    // a few milliseconds to find it, the same bytes.
    if (!options.before_step && options.frames >= kFramesWorthChoosingABuild)
        sim.set_chain_build(fastest_chain_build(sim));
    std::uint64_t done = 0;
    while (done < options.frames) {
        const std::size_t frames = static_cast<std::size_t>(
            std::min<std::uint64_t>(options.block_frames, options.frames - done));
        if (!options.before_step) {
            // Nothing to do between steps: the block in one call, which a bowed chain runs in
            // its own loop (Simulation::run() stops after a tick whose sound or probes are not
            // finite, where the steps below stop).
            const Simulation::ProbeRows rows{.values = probe_count ? probes.data() : nullptr};
            const std::size_t ran = sim.run({audio.data(), frames}, rows);
            const double* const last_row = probes.data() + (ran - 1) * probe_count;
            if (ran < frames || !std::isfinite(audio[ran - 1]) ||
                !std::all_of(last_row, last_row + probe_count,
                             [](double v) { return std::isfinite(v); }))
                throw_blow_up(sim);
        } else {
            for (std::size_t i = 0; i < frames; ++i) {
                options.before_step(sim);
                sim.step();
                audio[i] = sim.output();
                if (!std::isfinite(audio[i])) throw_blow_up(sim);
                for (std::size_t p = 0; p < probe_count; ++p) {
                    probes[i * probe_count + p] = sim.probe(p);
                    if (!std::isfinite(probes[i * probe_count + p])) throw_blow_up(sim);
                }
            }
        }
        // Masses that feed neither output nor probe: once per block, before it is handed on.
        if (find_blown_up_element(sim)) throw_blow_up(sim);
        sink({done, frames, audio.data(), probe_count ? probes.data() : nullptr, probe_count});
        done += frames;
    }
}

}  // namespace archet
