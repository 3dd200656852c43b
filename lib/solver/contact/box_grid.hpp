#pragma once
// A uniform grid over axis-aligned boxes, rebuilt from scratch for one state:
// the host broad phase of solver/contact/surface_contacts (what /contact
// records per frame). Every box goes into the one cell that holds its
// centre; the cell side is the longest box side (at most kMaxSpread times
// the median one), so a box reaches at most half a cell beyond its cell and
// a query visits the cells within half a cell of its own box. The cells are
// hashed by three large primes into a table of two to four times the boxes
// (Teschner et al. 2003) and filled by a counting sort; a bucket entry holds
// its cell and its bounds, so a bucket is scanned without looking
// elsewhere, and every overlapping box is reported once. Boxes longer than
// the cell (a stretched or blown-up triangle) are kept aside and tested
// against every query; non-finite boxes are never reported.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace atssim::solver {

class BoxGrid {
 public:
  using Box = Eigen::AlignedBox3d;
  static constexpr double kMaxSpread = 4.0;
  static constexpr std::int64_t kMaxQueryCells = 4096;  // beyond: a query scans every box

  explicit BoxGrid(std::vector<Box> boxes);

  // Calls hit(j) once for every box j that overlaps q (borders included).
  template <typename Hit>
  void query(const Box& q, Hit&& hit) const;

  int size() const { return static_cast<int>(boxes_.size()); }
  const Box& box(int j) const { return boxes_[j]; }
  double cell() const { return cell_; }

 private:
  // A box in a bucket: its cell, its bounds in float rounded outward (a
  // first cut before the exact test) and its id.
  struct Entry {
    std::int32_t cell[3];
    float lo[3], hi[3];
    int id;
  };
  std::int32_t coordinate(double v) const;
  // Teschner's hash, its bits mixed upward by a Fibonacci multiply, the top
  // `bits_` of them taken (a table of 2^bits_ buckets: no division).
  std::uint32_t bucket(std::int32_t x, std::int32_t y, std::int32_t z) const {
    const std::uint32_t h =
        (std::uint32_t(x) * 73856093u) ^ (std::uint32_t(y) * 19349663u) ^ (std::uint32_t(z) * 83492791u);
    return static_cast<std::uint32_t>((std::uint64_t(h) * 0x9E3779B97F4A7C15ull) >> (64 - bits_));
  }

  double cell_ = 1.0, inv_cell_ = 1.0;
  int bits_ = 1;
  std::uint32_t table_ = 2;  // 2^bits_
  std::vector<Box> boxes_;
  std::vector<int> large_;      // boxes longer than a cell
  std::vector<int> gridded_;    // the other finite ones
  std::vector<int> start_;      // per bucket, its first entry; table_ + 1
  std::vector<Entry> entries_;  // bucket by bucket
};

template <typename Hit>
void BoxGrid::query(const Box& q, Hit&& hit) const {
  if (!q.min().allFinite() || !q.max().allFinite() || q.isEmpty()) return;
  std::int32_t lo[3], hi[3];
  std::int64_t cells = 1;
  for (int k = 0; k < 3; ++k) {
    lo[k] = coordinate(q.min()[k] - 0.5 * cell_);
    hi[k] = coordinate(q.max()[k] + 0.5 * cell_);
    cells *= std::int64_t(hi[k]) - lo[k] + 1;
  }
  if (cells > kMaxQueryCells) {
    for (int j : gridded_)
      if (boxes_[j].intersects(q)) hit(j);
  } else {
    const float qlo[3] = {float(q.min()[0]), float(q.min()[1]), float(q.min()[2])};
    const float qhi[3] = {float(q.max()[0]), float(q.max()[1]), float(q.max()[2])};
    for (std::int32_t z = lo[2]; z <= hi[2]; ++z) {
      for (std::int32_t y = lo[1]; y <= hi[1]; ++y) {
        for (std::int32_t x = lo[0]; x <= hi[0]; ++x) {
          const std::uint32_t h = bucket(x, y, z);
          for (int k = start_[h]; k < start_[h + 1]; ++k) {
            const Entry& e = entries_[k];
            if (e.cell[0] != x || e.cell[1] != y || e.cell[2] != z) continue;  // another cell, same bucket
            if (e.lo[0] > qhi[0] || e.lo[1] > qhi[1] || e.lo[2] > qhi[2] || e.hi[0] < qlo[0] || e.hi[1] < qlo[1] ||
                e.hi[2] < qlo[2])
              continue;
            if (boxes_[e.id].intersects(q)) hit(e.id);
          }
        }
      }
    }
  }
  for (int j : large_)
    if (boxes_[j].intersects(q)) hit(j);
}

}  // namespace atssim::solver
