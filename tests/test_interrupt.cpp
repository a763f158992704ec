// The C++ front ends' interrupt handler (requests/interrupt.h) against a blocking system call: the
// first SIGTERM must reach a process waiting in one (a batch system stopping a job blocked on a
// read), so the call fails with EINTR instead of resuming its wait. Run in a child process (a
// death test), whose stop flag the signal sets for good.
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <thread>

#include "requests/interrupt.h"

namespace tripath {
namespace {

// Reads from a pipe nothing is written to until 2 s after a SIGTERM was sent to the reading
// thread: exits 0 if the read failed with EINTR and the stop flag is set, 1 if the read waited on
// for the byte (a handler installed with SA_RESTART, as std::signal installs it), 2 otherwise.
[[noreturn]] void readThroughASignal() {
    const std::atomic<bool>* stop = installInterruptHandler();
    int fds[2];
    if (pipe(fds) != 0) std::_Exit(2);
    const pthread_t reader = pthread_self();
    std::thread sender([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        pthread_kill(reader, SIGTERM);
        std::this_thread::sleep_for(std::chrono::seconds(2));
        const char byte = 0;
        if (write(fds[1], &byte, 1) != 1) std::_Exit(2);
    });
    sender.detach();
    char byte;
    const ssize_t got = read(fds[0], &byte, 1);
    if (got == 1) std::_Exit(1);
    std::_Exit(got == -1 && errno == EINTR && stop->load() && interruptSignal() == SIGTERM ? 0 : 2);
}

TEST(Interrupt, ASignalInterruptsABlockingCall) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(readThroughASignal(), testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace tripath
