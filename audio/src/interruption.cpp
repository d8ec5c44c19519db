#include "archet/interruption.hpp"

#include <signal.h>

#include <atomic>
#include <iterator>

namespace archet {

namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

// Lock-free, so that the handler may store to it.
std::atomic<int> received{0};
static_assert(std::atomic<int>::is_always_lock_free);

struct sigaction previous[std::size(kSignals)];

extern "C" void on_signal(int signal) {
    int none = 0;
    received.compare_exchange_strong(none, signal);  // the first one is the reason
}

}  // namespace

InterruptionGuard::InterruptionGuard(bool second_ends_at_once) {
    received.store(0);
    struct sigaction action {};
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    // Interrupted writes resume rather than fail; a second signal may have its default effect.
    action.sa_flags = SA_RESTART | (second_ends_at_once ? SA_RESETHAND : 0);
    for (std::size_t i = 0; i < std::size(kSignals); ++i) {
        sigaction(kSignals[i], &action, &previous[i]);
        // A signal the caller ignores stays ignored (`nohup archet render ...`, a background
        // job's SIGINT): it was not meant to stop us.
        if (previous[i].sa_handler == SIG_IGN) sigaction(kSignals[i], &previous[i], nullptr);
    }
}

InterruptionGuard::~InterruptionGuard() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
        sigaction(kSignals[i], &previous[i], nullptr);
}

int interruption_signal() {
    return received.load(std::memory_order_relaxed);
}

std::string signal_name(int signal) {
    switch (signal) {
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
        case SIGHUP:
            return "SIGHUP";
        default:
            return "signal " + std::to_string(signal);
    }
}

Interrupted::Interrupted(int signal, const std::string& what)
    : std::runtime_error("interrupted by " + signal_name(signal) + ": " + what), signal_(signal) {}

void throw_if_interrupted(const std::string& what) {
    if (const int signal = interruption_signal()) throw Interrupted(signal, what);
}

}  // namespace archet
