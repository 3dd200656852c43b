#include "solver/contact/box_grid.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace atssim::solver {

namespace {

// v in float, a little below (down) or above it: the float value is within
// 2^-24 of v relative, the margin 2^-22 (plus the smallest normal float).
float rounded(double v, bool down) {
  const float f = static_cast<float>(v);
  const float margin = std::abs(f) * 0x1p-22f + 1.2e-38f;
  return down ? f - margin : f + margin;
}

bool finite(const BoxGrid::Box& b) { return b.min().allFinite() && b.max().allFinite() && !b.isEmpty(); }

// The longest box side, at most kMaxSpread times the median one.
double cell_side(const std::vector<BoxGrid::Box>& boxes) {
  std::vector<double> sides;
  sides.reserve(boxes.size());
  for (const BoxGrid::Box& b : boxes)
    if (finite(b)) sides.push_back(b.sizes().maxCoeff());
  if (sides.empty()) return 1.0;
  auto mid = sides.begin() + sides.size() / 2;
  std::nth_element(sides.begin(), mid, sides.end());
  const double longest = *std::max_element(sides.begin(), sides.end());
  const double side = std::min(longest, BoxGrid::kMaxSpread * *mid);
  return side > 0.0 ? side : 1.0;  // points only: any side
}

}  // namespace

BoxGrid::FloatBox BoxGrid::FloatBox::outward(const Box& b) {
  FloatBox f;
  for (int k = 0; k < 3; ++k) {
    f.lo[k] = rounded(b.min()[k], true);
    f.hi[k] = rounded(b.max()[k], false);
  }
  return f;
}

// A cell coordinate, clamped so that a far box still has one.
std::int32_t BoxGrid::coordinate(double v) const {
  return static_cast<std::int32_t>(std::clamp(std::floor(v * inv_cell_), -1.0e9, 1.0e9));
}

BoxGrid::BoxGrid(std::vector<Box> boxes, double margin) : boxes_(std::move(boxes)), margin_(std::max(margin, 0.0)) {
  const double side = cell_side(boxes_);
  // A little over: a box's reach then stays strictly inside the 27 cells
  // of for_each_near, rounding of the cell coordinates included.
  cell_ = (side + 2.0 * margin_) * (1.0 + 0x1p-20);
  inv_cell_ = 1.0 / cell_;
  const int n = size();
  std::vector<Entry> entry(n);
  for (int i = 0; i < n; ++i) {
    const Box& b = boxes_[i];
    if (!finite(b)) continue;
    if (b.sizes().maxCoeff() > side) {
      large_.push_back(i);
      large_bounds_.push_back(FloatBox::outward(b));
      continue;
    }
    gridded_.push_back(i);
    Entry& e = entry[i];
    const Eigen::Vector3d centre = b.center();
    for (int k = 0; k < 3; ++k) {
      e.cell[k] = coordinate(centre[k]);
    }
    e.bounds = FloatBox::outward(b);
    e.id = i;
  }
  bits_ = 1;
  while ((std::size_t(1) << bits_) < 2 * gridded_.size() && bits_ < 31) ++bits_;
  table_ = std::uint32_t(1) << bits_;
  start_.assign(table_ + 1, 0);
  for (int i : gridded_) ++start_[bucket(entry[i].cell[0], entry[i].cell[1], entry[i].cell[2]) + 1];
  for (std::uint32_t h = 0; h < table_; ++h) start_[h + 1] += start_[h];
  entries_.resize(gridded_.size());
  std::vector<int> cursor(start_.begin(), start_.end() - 1);
  for (int i : gridded_) entries_[cursor[bucket(entry[i].cell[0], entry[i].cell[1], entry[i].cell[2])]++] = entry[i];
  // Within a bucket, the cells apart: a cell's boxes side by side, ids
  // ascending.
  const auto by_cell = [](const Entry& a, const Entry& b) {
    return std::tie(a.cell[0], a.cell[1], a.cell[2], a.id) < std::tie(b.cell[0], b.cell[1], b.cell[2], b.id);
  };
  for (std::uint32_t h = 0; h < table_; ++h)
    if (start_[h + 1] - start_[h] > 1)
      std::sort(entries_.begin() + start_[h], entries_.begin() + start_[h + 1], by_cell);
  slot_.assign(boxes_.size(), -1);
  for (std::size_t k = 0; k < entries_.size(); ++k) slot_[entries_[k].id] = static_cast<int>(k);
}

}  // namespace atssim::solver
