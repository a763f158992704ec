// Warnings about input that was accepted but not fully used (ignored glTF features, dropped
// triangles): reported through a sink so tests can capture them (the glTF loader sends each
// distinct message once).
#pragma once
#include <functional>
#include <string>

namespace tripath {

using WarningSink = std::function<void(const std::string&)>;

// The default sink: "warning: <message>" on a line of its own on stderr.
void printWarning(const std::string& message);

}  // namespace tripath
