#include "core/warnings.h"

#include <iostream>

#include "core/error.h"

namespace tripath {

void printWarning(const std::string& message) { std::cerr << "warning: " << oneLine(message) << '\n'; }

}  // namespace tripath
