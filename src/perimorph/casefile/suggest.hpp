#pragma once
// "Did you mean ...?" for misspelt keys and names in the case file.

#include <string>
#include <string_view>
#include <vector>

namespace perimorph::casefile {

/// Edit (Levenshtein) distance between a and b, ignoring ASCII case:
/// insertions, deletions and substitutions each cost 1.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word` by edit_distance, if that distance is at
/// most max(2, word.size() / 3) and less than the longer of the two lengths
/// (so "x" does not suggest "E"); failing that, the first candidate that
/// starts with `word` if `word` has 3 or more characters ("dir" suggests
/// "directory"); otherwise "". Ties go to the earlier candidate. An empty
/// candidate list gives "".
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace perimorph::casefile
