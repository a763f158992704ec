// Escaping text for HTML, which the comparison's and the benchmark's report pages write.
#pragma once
#include <string>

namespace tripath {

inline std::string escapeMarkup(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '"') out += "&quot;";
        else out += c;
    }
    return out;
}

}  // namespace tripath
