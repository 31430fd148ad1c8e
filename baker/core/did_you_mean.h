// "Did you mean …?" for unknown keys: the closest known name by edit distance.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace rockbake {

// Levenshtein distance (insertions, deletions, substitutions; each costs 1).
std::size_t editDistance(const std::string& a, const std::string& b);

// The candidate closest to `name`, when it is close enough to be a likely
// typo: at most max(2, |name| / 3) edits away. Ties go to the earlier candidate.
std::optional<std::string> closestName(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace rockbake
