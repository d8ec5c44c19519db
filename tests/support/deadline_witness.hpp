#pragma once
// A witness of the machine's own real-time behaviour, for tests that assert "no xrun".
//
// An xrun means a thread missed a deadline. On a virtual machine whose host takes the virtual
// CPUs away for milliseconds at a time (steal time), every program misses deadlines, however
// little it does. The witness runs, on every CPU, a top-priority SCHED_FIFO thread that does
// nothing but wake four times a period, and counts the stalls longer than half a period (a stall
// that long, at the wrong moment, costs a period's deadline; a machine that keeps real-time
// deadlines wakes such a thread within tens of microseconds). Waking once a period, it would miss
// most of the stalls that begin just after a wake-up and end before the next, while the device's
// deadlines, at another phase, fall inside them. When the witness misses
// none, an xrun is the program's; when it misses some, the machine could not have kept the deadline
// for anyone, and a test says so instead of blaming the code.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace archet::test {

class DeadlineWitness {
  public:
    explicit DeadlineWitness(std::chrono::nanoseconds period);
    ~DeadlineWitness();
    DeadlineWitness(const DeadlineWitness&) = delete;
    DeadlineWitness& operator=(const DeadlineWitness&) = delete;

    void stop();

    /// Deadlines missed on any CPU: a stall longer than half a period misses one, and one more
    /// for each whole period it lasted. A wake-up L late ends a stall of L to L + a quarter
    /// period (it began at most a quarter period before the wake-up was due); the middle counts.
    std::uint64_t missed() const { return missed_.load(); }
    /// The same with the stalls merged across CPUs where they overlap: a stall of the whole
    /// machine, which every CPU's thread sees, counts once, as a stall of one CPU does. Call
    /// after stop().
    std::uint64_t missed_by_the_machine() const;
    double worst_lateness_us() const { return static_cast<double>(worst_ns_.load()) / 1000.0; }
    bool realtime() const { return realtime_.load(); }
    /// The CPUs watched, a thread each.
    std::size_t cpus() const { return threads_.size(); }
    /// One sentence for a test's message; after stop().
    std::string describe() const;

  private:
    struct Stall {
        std::int64_t begin, end;  ///< ns, CLOCK_MONOTONIC: the middle estimate, as counted
    };
    void watch(int cpu, std::vector<Stall>& stalls);

    static constexpr int kWakeupsPerPeriod = 4;
    std::chrono::nanoseconds period_;
    std::atomic<bool> running_{true}, realtime_{true};
    std::atomic<std::uint64_t> missed_{0}, worst_ns_{0}, wakeups_{0};
    std::vector<std::vector<Stall>> stalls_;  ///< one list per thread, read after stop()
    std::vector<std::thread> threads_;
};

}  // namespace archet::test
