// The host broad phase of the surface record (solver/contact/box_grid):
// every overlapping box reported exactly once, as a brute-force scan over
// all boxes finds them, with stretched boxes, far boxes, points and
// non-finite boxes among them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "solver/contact/box_grid.hpp"

using atssim::solver::BoxGrid;
using Box = BoxGrid::Box;

namespace {

std::vector<Box> random_boxes(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> where(-1.0, 1.0), size(0.0, 0.05);
  std::vector<Box> boxes;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d lo(where(rng), 0.1 * where(rng), where(rng));
    boxes.emplace_back(lo, lo + Eigen::Vector3d(size(rng), size(rng), size(rng)));
  }
  return boxes;
}

bool finite(const Box& b) { return b.min().allFinite() && b.max().allFinite(); }

// Hit counts per box of one query, by the grid and by brute force (which
// skips the non-finite boxes as the grid does).
void check_query(const BoxGrid& grid, const std::vector<Box>& boxes, const Box& q) {
  std::vector<int> found(boxes.size(), 0), expected(boxes.size(), 0);
  grid.query(q, [&](int j) { ++found[j]; });
  for (std::size_t j = 0; j < boxes.size(); ++j) expected[j] = finite(q) && finite(boxes[j]) && boxes[j].intersects(q);
  REQUIRE(found == expected);
}

}  // namespace

TEST_CASE("the box grid reports every overlapping box once, as a brute-force scan does", "[contact][box_grid]") {
  std::vector<Box> boxes = random_boxes(2000, 7);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  boxes.emplace_back(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));           // longer than any cell
  boxes.emplace_back(Eigen::Vector3d(1e6, 1e6, 1e6), Eigen::Vector3d(1e6, 1e6, 1e6));  // a far point
  boxes.emplace_back(Eigen::Vector3d(0.1, 0.0, 0.1), Eigen::Vector3d(0.1, 0.0, 0.1));  // a point
  boxes.emplace_back(Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(0, 0, 0));            // never reported
  boxes.emplace_back(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(INFINITY, 0, 0));       // never reported
  boxes.push_back(Box());                                                              // empty: never reported
  const BoxGrid grid(boxes);
  CHECK(grid.size() == static_cast<int>(boxes.size()));
  for (const Box& q : boxes) check_query(grid, boxes, q);
  // Queries of other sizes: points, a box wider than the grid's query
  // limit, one touching another box at a face only.
  for (const Box& q : random_boxes(300, 11)) check_query(grid, boxes, Box(q.center()));
  check_query(grid, boxes, Box(Eigen::Vector3d(-1e3, -1e3, -1e3), Eigen::Vector3d(1e3, 1e3, 1e3)));
  const Box touching(Eigen::Vector3d(boxes[0].max().x(), boxes[0].min().y(), boxes[0].min().z()),
                     Eigen::Vector3d(boxes[0].max().x() + 0.1, boxes[0].max().y(), boxes[0].max().z()));
  check_query(grid, boxes, touching);
  int hits = 0;
  grid.query(touching, [&](int j) { hits += j == 0; });
  CHECK(hits == 1);  // borders count
}

TEST_CASE("the box grid holds boxes that all hash into one cell and boxes of zero size", "[contact][box_grid]") {
  // Every box the same: one cell, every query meets all of them.
  const std::vector<Box> same(50, Box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.01, 0.01, 0.01)));
  const BoxGrid grid(same);
  int hits = 0;
  grid.query(same[0], [&](int) { ++hits; });
  CHECK(hits == 50);
  // Points only (every side 0): each found by its own query alone.
  std::vector<Box> points;
  points.reserve(100);
  for (int i = 0; i < 100; ++i) points.emplace_back(Eigen::Vector3d(0.01 * i, 0, 0), Eigen::Vector3d(0.01 * i, 0, 0));
  const BoxGrid point_grid(points);
  for (const Box& q : points) check_query(point_grid, points, q);
}

TEST_CASE("with a margin, the boxes near a box's cell hold every box that a query within the margin meets",
          "[contact][box_grid]") {
  // Random boxes, stretched and non-finite ones among them; every query is
  // a gridded box widened by the margin, or a box inside that.
  std::vector<Box> boxes = random_boxes(3000, 5);
  boxes.emplace_back(Eigen::Vector3d(-1, -0.1, -1), Eigen::Vector3d(1, 0.1, 1));  // kept aside
  boxes.emplace_back(Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d(0, 0, 0));       // never listed
  const double margin = 0.02;
  const BoxGrid grid(boxes, margin);
  std::vector<int> led(boxes.size(), 0);
  int gridded = 0;
  for (std::size_t j = 0; j < boxes.size(); ++j) {
    const int id = static_cast<int>(j);
    if (grid.leads(id)) grid.for_each_cellmate(id, [&](int k) { ++led[k]; });
    if (!grid.gridded(id)) continue;
    ++gridded;
    std::vector<int> near(boxes.size(), 0);
    bool bounds_hold = true;
    grid.for_each_near(id, [&](int k, const BoxGrid::FloatBox& b) {
      ++near[k];
      for (int a = 0; a < 3; ++a)
        bounds_hold = bounds_hold && b.lo[a] <= boxes[k].min()[a] && b.hi[a] >= boxes[k].max()[a];
    });
    CHECK(bounds_hold);
    Box q = boxes[j];
    q.min().array() -= margin;
    q.max().array() += margin;
    int missed = 0, twice = 0;
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      twice += near[k] > 1;
      if (finite(boxes[k]) && boxes[k].intersects(q) && near[k] == 0) ++missed;
    }
    CHECK(missed == 0);
    CHECK(twice == 0);
  }
  CHECK(gridded == 3000);  // the stretched box and the NaN one are not in the grid
  // Every box is in exactly one cell's group (each box out of the grid alone in its).
  CHECK(std::count(led.begin(), led.end(), 1) == static_cast<long>(boxes.size()));
}
