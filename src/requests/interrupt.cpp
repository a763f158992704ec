#include "requests/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <cstdlib>

namespace tripath {

namespace {
std::atomic<bool> gStop{false};
std::atomic<int> gSignal{0};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

void onInterrupt(int signal) {
    int none = 0;
    gSignal.compare_exchange_strong(none, signal);  // the first one is the one reported
    if (gStop.exchange(true)) {  // the second one: give up at once, saying so (write is async-signal-safe)
        static constexpr char kLine[] = "interrupted again: exiting at once, without writing what the render has\n";
        [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, kLine, sizeof kLine - 1);
        std::_Exit(128 + gSignal.load());
    }
}
}  // namespace

const std::atomic<bool>* installInterruptHandler() {
    // Without SA_RESTART, a blocking call the signal arrives in returns (EINTR) rather than
    // waiting on, as std::signal would have it: the caller gets to see the stop request.
    struct sigaction action = {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    return &gStop;
}

int interruptSignal() { return gSignal.load(); }

}  // namespace tripath
