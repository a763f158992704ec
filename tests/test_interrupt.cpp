// Interrupts. The C++ front ends' handler (requests/interrupt.h) against a blocking system call:
// the first SIGTERM must reach a process waiting in one (a batch system stopping a job blocked on a
// read), so the call fails with EINTR instead of resuming its wait; run in a child process (a
// death test), whose stop flag the signal sets for good. And the stop flag against mlt's
// bootstrap, the one part of a render that comes before its first pass.
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <thread>

#include "geometry/scene.h"
#include "integrators/render.h"
#include "requests/interrupt.h"
#include "requests/render_request.h"
#include "scenes/builtin_scenes.h"

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

// A stop request during mlt's bootstrap (the largest, 10^7 samples: 20 s on two busy cores) ends
// the render within moments, before any pass: a result that holds no pass and says so, so that the
// front ends write nothing. Without the bootstrap looking at the flag the render runs the whole
// bootstrap and a pass first.
TEST(Interrupt, MltStopsInItsBootstrapBeforeAnyPass) {
    const Scene scene(builtinScene("cornell"), 8, 8, [](const std::string&) {});
    IntegratorSettings is;
    is.metropolis.bootstrap = int64_t(kBootstrapRange.max);
    const auto mlt = makeIntegrator("mlt", is);
    std::atomic<bool> stop{false};
    RenderSettings rs;
    rs.spp = 4;
    rs.stop = &stop;
    std::thread stopper([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        stop = true;
    });
    const auto start = std::chrono::steady_clock::now();
    const RenderResult r = render(scene, *mlt, rs);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stopper.join();
    EXPECT_LT(seconds, 5.0);
    EXPECT_TRUE(r.interrupted);
    EXPECT_TRUE(r.interruptedBeforeAnyPass);
    EXPECT_EQ(r.passes, 0);
}

}  // namespace
}  // namespace tripath
