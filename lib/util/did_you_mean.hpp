#pragma once
// Suggests the closest known word for a misspelt one (Levenshtein distance).
#include <span>
#include <string>
#include <string_view>

namespace atssim {

std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word`, or "" when none is close enough to be a
// plausible typo (distance > max(2, |word|/3)).
std::string closest_match(std::string_view word, std::span<const std::string_view> candidates);

}  // namespace atssim
