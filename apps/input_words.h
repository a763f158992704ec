// Words from the command line in error messages: the known name nearest to a typo, for "did you
// mean …?" (a long argument is cut by clipped, core/error.h).
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace tripath::app {

// The name of `names` fewest single-character edits (insertions, deletions, substitutions) away
// from `word`, if that is at most half the word's length (a word further from every name is no
// typo of one); the first such name on a tie.
std::optional<std::string> nearestName(const std::string& word, const std::vector<std::string>& names);

}  // namespace tripath::app
