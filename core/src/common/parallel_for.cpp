#include "archet/common/parallel_for.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <thread>
#include <vector>

namespace archet {

bool parallel_for(std::size_t count, int jobs, const std::function<void(std::size_t)>& work,
                  const std::atomic<bool>* cancel,
                  const std::function<void(std::size_t, std::size_t)>& progress) {
    std::atomic<std::size_t> next{0}, done{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
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
    };
    std::vector<std::thread> threads;
    const auto workers = static_cast<std::size_t>(std::max(1, jobs));
    for (std::size_t t = 0; t < std::min(workers, std::max<std::size_t>(count, 1)); ++t)
        threads.emplace_back(worker);
    while (done.load() < count && !failed.load() && !cancelled()) {
        if (progress) progress(done.load(), count);
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
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

}  // namespace archet
