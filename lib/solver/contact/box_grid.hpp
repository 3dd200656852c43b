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
//
// With a margin m, the cell is 2m longer and the boxes longer than the cell
// less 2m are kept aside: a query box within m of a gridded box j then
// meets only boxes whose centres lie in the 27 cells around j's, which
// for_each_near lists. The boxes of one cell share those 27 cells, so their
// queries can take one list of candidates (leads, for_each_cellmate): the
// table is visited once per cell rather than once per box.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace atssim::solver {

class BoxGrid {
 public:
  using Box = Eigen::AlignedBox3d;
  static constexpr double kMaxSpread = 4.0;
  static constexpr std::int64_t kMaxQueryCells = 4096;  // beyond: a query scans every box

  // A box's bounds in float, rounded outward (it holds the exact box): a
  // first cut before the exact test.
  struct FloatBox {
    float lo[3], hi[3];
    static FloatBox outward(const Box& b);
    bool overlaps(const FloatBox& o) const {
      return !(lo[0] > o.hi[0] || lo[1] > o.hi[1] || lo[2] > o.hi[2] || hi[0] < o.lo[0] || hi[1] < o.lo[1] ||
               hi[2] < o.lo[2]);
    }
  };

  explicit BoxGrid(std::vector<Box> boxes, double margin = 0.0);

  // Calls hit(j) once for every box j that overlaps q (borders included).
  template <typename Hit>
  void query(const Box& q, Hit&& hit) const;

  // Whether box j is in the grid (finite, not longer than the cell less 2m).
  bool gridded(int j) const { return slot_[j] >= 0; }
  // Whether box j is the first (lowest id) of the boxes in its cell; a box
  // not in the grid is alone in its.
  bool leads(int j) const;
  // Calls f(k) for every box k in box j's cell, j among them, ids ascending.
  template <typename F>
  void for_each_cellmate(int j, F&& f) const;
  // For a gridded box j, calls near(k, bounds) for every box k that a query
  // within the margin of j, or of any box in j's cell, can meet: the gridded
  // boxes of the 27 cells around j's and the boxes kept aside, with k's
  // FloatBox.
  template <typename Near>
  void for_each_near(int j, Near&& near) const;

  int size() const { return static_cast<int>(boxes_.size()); }
  const Box& box(int j) const { return boxes_[j]; }
  double cell() const { return cell_; }

 private:
  // A box in a bucket: its cell, its FloatBox and its id.
  struct Entry {
    std::int32_t cell[3];
    FloatBox bounds;
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

  int bits_ = 1;
  std::uint32_t table_ = 2;  // 2^bits_
  std::vector<Box> boxes_;
  double margin_ = 0.0, cell_ = 1.0, inv_cell_ = 1.0;
  std::vector<int> large_;              // boxes longer than the cell less 2m
  std::vector<int> gridded_;            // the other finite ones
  std::vector<int> start_;              // per bucket, its first entry; table_ + 1
  std::vector<Entry> entries_;          // bucket by bucket, in a bucket cell by cell, in a cell ids ascending
  std::vector<int> slot_;               // per box, its entry; -1: not in the grid
  std::vector<FloatBox> large_bounds_;  // large_'s

  static bool same_cell(const Entry& a, const Entry& b) {
    return a.cell[0] == b.cell[0] && a.cell[1] == b.cell[1] && a.cell[2] == b.cell[2];
  }
  std::uint32_t bucket_of(const Entry& e) const { return bucket(e.cell[0], e.cell[1], e.cell[2]); }
};

inline bool BoxGrid::leads(int j) const {
  const int s = slot_[j];
  if (s < 0) return true;
  return s == start_[bucket_of(entries_[s])] || !same_cell(entries_[s - 1], entries_[s]);
}

template <typename F>
void BoxGrid::for_each_cellmate(int j, F&& f) const {
  const int s = slot_[j];
  if (s < 0) {
    f(j);
    return;
  }
  const std::uint32_t h = bucket_of(entries_[s]);
  int first = s;
  while (first > start_[h] && same_cell(entries_[first - 1], entries_[s])) --first;
  for (int k = first; k < start_[h + 1] && same_cell(entries_[k], entries_[s]); ++k) f(entries_[k].id);
}

template <typename Near>
void BoxGrid::for_each_near(int j, Near&& near) const {
  const Entry& own = entries_[slot_[j]];
  for (std::int32_t z = own.cell[2] - 1; z <= own.cell[2] + 1; ++z) {
    for (std::int32_t y = own.cell[1] - 1; y <= own.cell[1] + 1; ++y) {
      for (std::int32_t x = own.cell[0] - 1; x <= own.cell[0] + 1; ++x) {
        const std::uint32_t h = bucket(x, y, z);
        for (int k = start_[h]; k < start_[h + 1]; ++k) {
          const Entry& e = entries_[k];
          if (e.cell[0] == x && e.cell[1] == y && e.cell[2] == z) near(e.id, e.bounds);
        }
      }
    }
  }
  for (std::size_t k = 0; k < large_.size(); ++k) near(large_[k], large_bounds_[k]);
}

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
    const FloatBox qb = FloatBox::outward(q);
    for (std::int32_t z = lo[2]; z <= hi[2]; ++z) {
      for (std::int32_t y = lo[1]; y <= hi[1]; ++y) {
        for (std::int32_t x = lo[0]; x <= hi[0]; ++x) {
          const std::uint32_t h = bucket(x, y, z);
          for (int k = start_[h]; k < start_[h + 1]; ++k) {
            const Entry& e = entries_[k];
            if (e.cell[0] != x || e.cell[1] != y || e.cell[2] != z) continue;  // another cell, same bucket
            if (e.bounds.overlaps(qb) && boxes_[e.id].intersects(q)) hit(e.id);
          }
        }
      }
    }
  }
  for (int j : large_)
    if (boxes_[j].intersects(q)) hit(j);
}

}  // namespace atssim::solver
