#include "requests/interrupt.h"

#include <csignal>
#include <cstdlib>

namespace tripath {

namespace {
std::atomic<bool> gStop{false};
std::atomic<int> gSignal{0};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

void onInterrupt(int signal) {
    int none = 0;
    gSignal.compare_exchange_strong(none, signal);  // the first one is the one reported
    if (gStop.exchange(true)) std::_Exit(128 + gSignal.load());  // the second one: give up at once
}
}  // namespace

const std::atomic<bool>* installInterruptHandler() {
    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);
    return &gStop;
}

int interruptSignal() { return gSignal.load(); }

}  // namespace tripath
