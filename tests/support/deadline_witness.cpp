#include "deadline_witness.hpp"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <sstream>

namespace archet::test {
namespace {

std::int64_t monotonic_ns() {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

// The deadlines a stall of `stall` ns costs: one, and one more for each whole period it lasted.
std::uint64_t deadlines_missed_by(std::int64_t stall, std::int64_t period) {
    return 1 + static_cast<std::uint64_t>(stall / period);
}

}  // namespace

DeadlineWitness::DeadlineWitness(std::chrono::nanoseconds period) : period_(period) {
    cpu_set_t cpus;
    CPU_ZERO(&cpus);
    sched_getaffinity(0, sizeof cpus, &cpus);
    stalls_.resize(static_cast<std::size_t>(CPU_COUNT(&cpus)));
    for (auto& list : stalls_) list.reserve(4096);  // no allocation while watching, mostly
    std::size_t thread = 0;
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
        if (CPU_ISSET(cpu, &cpus)) {
            std::vector<Stall>& stalls = stalls_[thread++];
            threads_.emplace_back([this, cpu, &stalls] { watch(cpu, stalls); });
        }
}

DeadlineWitness::~DeadlineWitness() {
    stop();
}

void DeadlineWitness::stop() {
    running_.store(false);
    for (auto& t : threads_)
        if (t.joinable()) t.join();
}

void DeadlineWitness::watch(int cpu, std::vector<Stall>& stalls) {
    cpu_set_t only;
    CPU_ZERO(&only);
    CPU_SET(cpu, &only);
    pthread_setaffinity_np(pthread_self(), sizeof only, &only);
    // Above the audio threads (JACK's 10, the null sink's 70): nothing in the machine but the
    // kernel can delay it, so its lateness is the platform's.
    sched_param param{};
    param.sched_priority = sched_get_priority_max(SCHED_FIFO);
    if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) != 0) realtime_.store(false);

    const std::int64_t period = period_.count(), interval = period / kWakeupsPerPeriod;
    std::int64_t deadline = monotonic_ns();
    while (running_.load(std::memory_order_relaxed)) {
        deadline += interval;
        const timespec t{static_cast<time_t>(deadline / 1'000'000'000),
                         static_cast<long>(deadline % 1'000'000'000)};
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
        }
        const std::int64_t late = monotonic_ns() - deadline;
        wakeups_.fetch_add(1, std::memory_order_relaxed);
        auto worst = worst_ns_.load(std::memory_order_relaxed);
        while (late > static_cast<std::int64_t>(worst) &&
               !worst_ns_.compare_exchange_weak(worst, static_cast<std::uint64_t>(late))) {
        }
        // A stall of several periods misses the deadline of each: a device's driver counts
        // every cycle it could not serve (JACK reports an xrun per cycle).
        const std::int64_t stall = late + interval / 2;
        if (stall > period / 2) {
            missed_.fetch_add(deadlines_missed_by(stall, period), std::memory_order_relaxed);
            const std::int64_t woke = deadline + late;
            stalls.push_back({woke - stall, woke});
        }
        if (late > interval) deadline = monotonic_ns();  // start afresh, as a device would
    }
}

std::uint64_t DeadlineWitness::missed_by_the_machine() const {
    std::vector<Stall> all;
    for (const auto& list : stalls_) all.insert(all.end(), list.begin(), list.end());
    std::sort(all.begin(), all.end(),
              [](const Stall& a, const Stall& b) { return a.begin < b.begin; });
    const std::int64_t period = period_.count();
    std::uint64_t missed = 0;
    for (std::size_t i = 0; i < all.size();) {
        Stall merged = all[i++];
        while (i < all.size() && all[i].begin <= merged.end)
            merged.end = std::max(merged.end, all[i++].end);
        missed += deadlines_missed_by(merged.end - merged.begin, period);
    }
    return missed;
}

std::string DeadlineWitness::describe() const {
    std::ostringstream s;
    s << "this machine's own " << (realtime() ? "top-priority SCHED_FIFO" : "normal-priority")
      << " witness threads (one per CPU, waking " << kWakeupsPerPeriod << " times a period of "
      << static_cast<double>(period_.count()) / 1000.0 << " us) missed " << missed()
      << " deadlines in " << wakeups_.load()
      << " wake-ups (one per stall longer than half a period, and one more per whole period it "
         "lasted; "
      << missed_by_the_machine() << " with each stall counted once across CPUs); worst wake-up "
      << worst_lateness_us() << " us late";
    return s.str();
}

}  // namespace archet::test
