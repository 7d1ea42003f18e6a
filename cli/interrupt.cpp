#include "interrupt.h"

#include <unistd.h>

#include <csignal>

namespace edacrt::cli {
namespace {

// A signal handler may only touch lock-free atomics (and call async-signal-safe functions).
static_assert(std::atomic<bool>::is_always_lock_free);
std::atomic<bool> interrupt_seen{false};
std::atomic<bool> keep_work{false};

extern "C" void on_interrupt(int) {
    // Nothing to keep yet, or a second Ctrl-C: the user wants out now.
    if (!keep_work.load() || interrupt_seen.exchange(true)) _exit(kInterruptedStatus);
}

}  // namespace

void catch_interrupts() {
    struct sigaction old {};
    if (sigaction(SIGINT, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) return;
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;  // reads and writes in progress carry on
    sigaction(SIGINT, &action, nullptr);
}

void keep_work_on_interrupt() { keep_work = true; }

const std::atomic<bool>& interrupted() { return interrupt_seen; }

}  // namespace edacrt::cli
