// Escaping text for HTML and SVG, which the compare report and the charts both write.
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
