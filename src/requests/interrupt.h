// Ctrl-C for a C++ front end: the first SIGINT or SIGTERM asks every render that watches the flag
// (RenderSettings::stop) to stop at its next pass boundary, so the image so far can be written (mlt
// in its bootstrap stops at once, with no pass and so no image); a second one exits at once, with
// a line on stderr saying so. The signal is remembered, so that the front end, having written what
// it has, can still exit as interrupted (128 + the signal's number, as a shell reports a process
// the signal ended): a batch job killed at its time limit must not look finished. A signal
// interrupts a blocking system call (it fails with EINTR) rather than letting it wait on. (The
// Python module lets Python's own handler do this instead.)
#pragma once
#include <atomic>

namespace tripath {

// Installs the handlers (again: idempotent) and returns the flag they set.
const std::atomic<bool>* installInterruptHandler();

// The first signal the handlers caught (SIGINT or SIGTERM), or 0 if none.
int interruptSignal();

}  // namespace tripath
