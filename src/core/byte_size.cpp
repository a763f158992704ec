// Amounts of memory read and written as text (byte_size.h).
#include "core/byte_size.h"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

namespace tripath {

namespace {
constexpr std::array<char, 5> kUnits{'\0', 'K', 'M', 'G', 'T'};  // 1024^index
}  // namespace

std::optional<uint64_t> parseByteSize(std::string_view text) {
    size_t digits = 0;
    while (digits < text.size() && (std::isdigit(static_cast<unsigned char>(text[digits])) || text[digits] == '.')) ++digits;
    std::string_view number = text.substr(0, digits), unit = text.substr(digits);
    if (number.empty() || number.front() == '.' || number.back() == '.') return std::nullopt;
    double value = 0;
    const auto [stop, ec] = std::from_chars(number.data(), number.data() + number.size(), value, std::chars_format::fixed);
    if (ec != std::errc{} || stop != number.data() + number.size()) return std::nullopt;
    int power = 0;
    if (!unit.empty()) {
        const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(unit.front())));
        for (size_t i = 1; i < kUnits.size(); ++i)
            if (kUnits[i] == letter) power = int(i);
        unit.remove_prefix(1);
        std::string rest(unit);
        for (char& c : rest) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (power == 0 || !(rest.empty() || rest == "b" || rest == "ib")) return std::nullopt;
    }
    const double bytes = std::round(std::ldexp(value, 10 * power));
    if (!(bytes < 18446744073709551616.0)) return std::nullopt;  // 2^64
    return static_cast<uint64_t>(bytes);
}

std::string bytesText(uint64_t bytes) {
    if (bytes < 1024) return fmt::format("{} B", bytes);
    int power = 1;
    while (power + 1 < int(kUnits.size()) && bytes >= (uint64_t(1) << (10 * (power + 1)))) ++power;
    const double value = std::ldexp(double(bytes), -10 * power);
    const int decimals = value < 10 ? 2 : value < 100 ? 1 : 0;
    return fmt::format("{:.{}f} {}iB", value, decimals, kUnits[size_t(power)]);
}

}  // namespace tripath
