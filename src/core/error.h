// The one exception type for bad input: its message is the single line the user sees.
#pragma once
#include <stdexcept>
#include <string>

namespace tripath {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace tripath
