#include "core/warnings.h"

#include <iostream>

namespace tripath {

void printWarning(const std::string& message) { std::cerr << "warning: " << message << '\n'; }

}  // namespace tripath
