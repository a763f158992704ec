// The one exception type for bad input: its message is the single line the user sees, whatever
// text from a file or a flag it quotes (a material named "a\nb" is written a\nb, not on two lines).
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

namespace tripath {

// `text` with its control characters written as escapes (\n, \r, \t, \x1b, ...), so that a name
// or path taken from the input cannot break a message over lines or drive the terminal.
inline std::string oneLine(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else if (u < 0x20 || u == 0x7f) {
            char escape[5];
            std::snprintf(escape, sizeof escape, "\\x%02x", u);
            out += escape;
        } else
            out += c;
    }
    return out;
}

// `text` itself, or its first 40 characters and "..." when it is longer: a word from the command
// line or a value from a file, cut to what identifies it, so that a message stays one short line.
inline std::string clipped(const std::string& text) {
    constexpr size_t kShown = 40;
    return text.size() > kShown ? text.substr(0, kShown) + "..." : text;
}

struct InputError : std::runtime_error {
    explicit InputError(const std::string& message) : std::runtime_error(oneLine(message)) {}
};

}  // namespace tripath
