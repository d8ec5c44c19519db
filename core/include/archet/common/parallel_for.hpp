#pragma once
// Independent pieces of offline work (the points of a playability map, the strokes of a band
// search, the variants of a comparison) spread over threads. Each piece writes only its own
// result, so the outcome is the same on any number of threads.

#include <atomic>
#include <cstddef>
#include <functional>

namespace archet {

/// Runs work(i) for every i in [0, count) on `jobs` threads (at least one), calling
/// `progress(done, count)` from the caller's thread about ten times a second while they run.
/// Stops handing out pieces once `*cancel` is set or a piece throws; rethrows the first
/// exception a piece threw. Returns false when cancelled before every piece ran.
bool parallel_for(std::size_t count, int jobs, const std::function<void(std::size_t)>& work,
                  const std::atomic<bool>* cancel = nullptr,
                  const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The machine's cores (at least one).
int hardware_jobs();

}  // namespace archet
