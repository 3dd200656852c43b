#include <catch2/catch.hpp>

#include <array>
#include <string_view>

#include "util/did_you_mean.hpp"

using namespace atssim;

TEST_CASE("edit distance counts insertions, deletions and substitutions") {
  CHECK(edit_distance("stiffness", "stifness") == 1);
  CHECK(edit_distance("kitten", "sitting") == 3);
  CHECK(edit_distance("", "abc") == 3);
  CHECK(edit_distance("same", "same") == 0);
}

TEST_CASE("closest_match suggests a near key and nothing for a far one") {
  const std::array<std::string_view, 3> keys{"stiffness", "density", "compliance"};
  CHECK(closest_match("stifness", keys) == "stiffness");
  CHECK(closest_match("densty", keys) == "density");
  CHECK(closest_match("zebra", keys).empty());
}
