// Numbers read back from files tripath wrote and may find damaged or edited (a checkpoint's
// header, a reference's metadata): the whole text must be the number, within its range, or it is
// refused; no prefix is taken ("12x"), no sign wraps ("-5"), no overflow saturates.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

namespace tripath {

// `text` as a whole number from 0 to `max`: decimal digits and nothing else; nullopt for "",
// "-5", "+5", "abc", "12x", " 12" or a number above max.
std::optional<uint64_t> parseWholeNumber(std::string_view text, uint64_t max);

// `text` as a finite number from 0 to `max` (e.g. "0.25", "1e3"); nullopt for "nan", "inf", "-1",
// "1s", "" or a number above max.
std::optional<double> parseNonNegative(std::string_view text, double max);

}  // namespace tripath
