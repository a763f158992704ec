// Ctrl-C for a C++ front end: the first SIGINT or SIGTERM asks every render that watches the flag
// (RenderSettings::stop) to stop at its next pass boundary, so the image so far can be written; a
// second one exits at once. (The Python module lets Python's own handler do this instead.)
#pragma once
#include <atomic>

namespace tripath {

// Installs the handlers (again: idempotent) and returns the flag they set.
const std::atomic<bool>* installInterruptHandler();

}  // namespace tripath
