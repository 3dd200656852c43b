#pragma once
// The step both greedy colorings share (color_blocks.cpp, vertex_colors.cpp).
#include <vector>

namespace atssim::graph {

// The smallest color not marked `stamp` in `taken_by` (taken_by[c] == stamp:
// color c is used next to the item being colored), opening a new color when
// all are taken. Stamping with the item's id avoids clearing between items.
inline int first_free_color(std::vector<int>& taken_by, int stamp) {
  int c = 0;
  const int colors = static_cast<int>(taken_by.size());
  while (c < colors && taken_by[c] == stamp) ++c;
  if (c == colors) taken_by.push_back(-1);
  return c;
}

}  // namespace atssim::graph
