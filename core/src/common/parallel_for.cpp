#include "archet/common/parallel_for.hpp"

#include "archet/common/grid_sweep.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace archet {

bool parallel_for(std::size_t count, int jobs, const std::function<void(std::size_t)>& work,
                  const std::atomic<bool>* cancel,
                  const std::function<void(std::size_t, std::size_t)>& progress) {
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex mutex;
    std::condition_variable ended;  // a worker ran out of pieces
    auto cancelled = [&] { return cancel && cancel->load(); };
    auto worker = [&] {
        for (std::size_t i; !failed.load() && !cancelled() && (i = next.fetch_add(1)) < count;) {
            try {
                work(i);
            } catch (...) {
                if (!failed.exchange(true)) error = std::current_exception();
            }
            done.fetch_add(1);
        }
        std::lock_guard lock(mutex);
        ended.notify_one();
    };
    std::vector<std::thread> threads;
    const auto workers = std::min(static_cast<std::size_t>(std::max(1, jobs)), count);
    try {
        for (std::size_t t = 0; t < workers; ++t) threads.emplace_back(worker);
        // Progress about ten times a second, until the pieces are done or no longer handed out.
        for (std::unique_lock lock(mutex); done.load() < count && !failed.load() && !cancelled();) {
            if (progress) progress(done.load(), count);
            ended.wait_for(lock, std::chrono::milliseconds(100));
        }
    } catch (...) {  // a thread that could not start, or the progress: the others stop first
        failed = true;
        for (auto& t : threads) t.join();
        throw;
    }
    for (auto& t : threads) t.join();
    if (failed.load()) std::rethrow_exception(error);
    if (done.load() < count) return false;
    if (progress) progress(count, count);
    return true;
}

int hardware_jobs() {
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::vector<std::size_t> shard_points(std::size_t count, int shard, int shards) {
    if (shards < 1 || shard < 0 || shard >= shards)
        throw InputError("--shard", "expected I/N with 0 ≤ I < N");
    std::vector<std::size_t> mine;
    for (std::size_t i = static_cast<std::size_t>(shard); i < count;
         i += static_cast<std::size_t>(shards))
        mine.push_back(i);
    return mine;
}

}  // namespace archet
