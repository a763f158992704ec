#include "integrators/interrupt.h"

#include <csignal>
#include <cstdlib>

namespace tripath {

namespace {
std::atomic<bool> gStop{false};
void onInterrupt(int) {
    if (gStop.exchange(true)) std::_Exit(130);  // second Ctrl-C: give up at once
}
}  // namespace

const std::atomic<bool>* installInterruptHandler() {
    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);
    return &gStop;
}

}  // namespace tripath
