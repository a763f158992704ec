#include "input_words.h"

#include <algorithm>
#include <numeric>

namespace tripath::app {

namespace {

// Levenshtein distance, one row of the table at a time.
size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    std::iota(row.begin(), row.end(), size_t(0));
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
            diagonal = row[j];
            row[j] = std::min({substitute, row[j] + 1, row[j - 1] + 1});
        }
    }
    return row[b.size()];
}

}  // namespace

std::optional<std::string> nearestName(const std::string& word, const std::vector<std::string>& names) {
    std::optional<std::string> best;
    size_t bestDistance = std::max<size_t>(1, word.size() / 2) + 1;
    for (const std::string& name : names)
        if (const size_t d = editDistance(word, name); d < bestDistance) best = name, bestDistance = d;
    return best;
}

}  // namespace tripath::app
