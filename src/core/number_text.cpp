// Whole-text, range-checked number parsing (number_text.h).
#include "core/number_text.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace tripath {

std::optional<uint64_t> parseWholeNumber(std::string_view text, uint64_t max) {
    uint64_t value = 0;
    const char* end = text.data() + text.size();
    // from_chars takes no sign for an unsigned type and reports overflow rather than wrapping.
    const auto [stop, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc{} || stop != end || value > max) return std::nullopt;
    return value;
}

std::optional<double> parseNonNegative(std::string_view text, double max) {
    double value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc{} || stop != end || !std::isfinite(value) || !(value >= 0) || value > max) return std::nullopt;
    return value;
}

}  // namespace tripath
