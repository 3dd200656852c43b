#pragma once
// The alternative broad phase: a uniform spatial hash rebuilt every step
// (Teschner et al. 2003, "Optimized spatial hashing for collision detection
// of deformable objects": cells of a fixed size, hashed by three large
// primes into a table of about twice the primitives). Three tables: the
// triangles and the edges by every cell their box overlaps, the vertices by
// their cell; filled by a counting sort (count, prefix sum, scatter), so a
// bucket lists its primitives in id order. A query visits every cell of its
// box widened by r and takes a primitive only in the first cell the two
// boxes share (no duplicates), after checking that the primitive really
// covers the cell (another cell may hash to the same bucket). Two cells of
// one primitive that share a bucket put it there twice, side by side.
#include <cstdint>
#include <vector>

#include "broad_phase/surface_pairs.hpp"

namespace atssim::bench {

struct CellRange {
  int lo[3], hi[3];
};

struct HashGrid {
  float inv_cell = 1.0f;
  std::uint32_t table = 1;
  std::vector<Box> box;          // per primitive (unwidened)
  std::vector<CellRange> cells;  // per primitive, the cells its box overlaps
  std::vector<int> start;        // per bucket, offset into entries; table + 1
  std::vector<int> entries;      // primitive ids, bucket by bucket
};

inline std::uint32_t cell_hash(int x, int y, int z, std::uint32_t table) {
  return ((std::uint32_t(x) * 73856093u) ^ (std::uint32_t(y) * 19349663u) ^ (std::uint32_t(z) * 83492791u)) % table;
}

inline CellRange cells_of(const Box& b, float inv_cell) {
  CellRange c;
  for (int k = 0; k < 3; ++k) {
    c.lo[k] = static_cast<int>(std::floor(b.lo[k] * inv_cell));
    c.hi[k] = static_cast<int>(std::floor(b.hi[k] * inv_cell));
  }
  return c;
}

// The boxes and cell ranges of primitives [begin, end) (parallel-safe).
template <typename BoxOf>
void hash_boxes(HashGrid& g, BoxOf&& box_of, int begin, int end) {
  for (int i = begin; i < end; ++i) {
    g.box[i] = box_of(i);
    g.cells[i] = cells_of(g.box[i], g.inv_cell);
  }
}

template <typename Cell>
void for_each_cell(const CellRange& c, Cell&& cell) {
  for (int z = c.lo[2]; z <= c.hi[2]; ++z)
    for (int y = c.lo[1]; y <= c.hi[1]; ++y)
      for (int x = c.lo[0]; x <= c.hi[0]; ++x) cell(x, y, z);
}

// The counting sort of every primitive's cells into the table (serial).
inline void hash_fill(HashGrid& g) {
  g.start.assign(g.table + 1, 0);
  const int count = static_cast<int>(g.box.size());
  for (int i = 0; i < count; ++i)
    for_each_cell(g.cells[i], [&](int x, int y, int z) { ++g.start[cell_hash(x, y, z, g.table) + 1]; });
  for (std::uint32_t h = 0; h < g.table; ++h) g.start[h + 1] += g.start[h];
  g.entries.resize(g.start[g.table]);
  std::vector<int> cursor(g.start.begin(), g.start.end() - 1);
  for (int i = 0; i < count; ++i)
    for_each_cell(g.cells[i], [&](int x, int y, int z) { g.entries[cursor[cell_hash(x, y, z, g.table)]++] = i; });
}

inline void hash_resize(HashGrid& g, int count, float cell) {
  g.inv_cell = 1.0f / cell;
  g.table = 2u * static_cast<std::uint32_t>(count) + 1u;
  g.box.resize(count);
  g.cells.resize(count);
}

// Calls hit(j) once for every primitive j whose box overlaps q.
template <typename Hit>
void hash_walk(const HashGrid& g, const Box& q, Hit&& hit) {
  const CellRange c = cells_of(q, g.inv_cell);
  for_each_cell(c, [&](int x, int y, int z) {
    const std::uint32_t h = cell_hash(x, y, z, g.table);
    for (int k = g.start[h]; k < g.start[h + 1]; ++k) {
      const int j = g.entries[k];
      if (k > g.start[h] && g.entries[k - 1] == j) continue;  // two of j's cells share this bucket
      const CellRange& o = g.cells[j];
      if (x < o.lo[0] || x > o.hi[0] || y < o.lo[1] || y > o.hi[1] || z < o.lo[2] || z > o.hi[2]) continue;
      if (x != std::max(c.lo[0], o.lo[0]) || y != std::max(c.lo[1], o.lo[1]) || z != std::max(c.lo[2], o.lo[2]))
        continue;
      if (overlap(g.box[j], q)) hit(j);
    }
  });
}

// The three tables of one step.
struct SurfaceHash {
  HashGrid vertices, triangles, edges;
};

inline void hash_resize(SurfaceHash& h, const SelfContactLayout& s, int vertex_count, float cell) {
  hash_resize(h.vertices, vertex_count, cell);
  hash_resize(h.triangles, static_cast<int>(s.tris.size()), cell);
  hash_resize(h.edges, static_cast<int>(s.edges.size()), cell);
}

inline auto vertex_box_of(const std::vector<ats_vec3>& x) {
  return [&x](int i) { return point_box(x[i], 0.0f); };
}
inline auto triangle_box_of(const SelfContactLayout& s, const std::vector<ats_vec3>& x) {
  return [&s, &x](int t) { return triangle_box(x[s.tris[t][0]], x[s.tris[t][1]], x[s.tris[t][2]], 0.0f); };
}
inline auto edge_box_of(const SelfContactLayout& s, const std::vector<ats_vec3>& x) {
  return [&s, &x](int e) { return edge_box(x[s.edges[e][0]], x[s.edges[e][1]], 0.0f); };
}

// One step's tables, single-threaded. A vertex with no triangle is put in
// no cell (an empty range), as the queries skip it.
inline void hash_build(SurfaceHash& h, const SelfContactLayout& s, const std::vector<ats_vec3>& x) {
  const int n = static_cast<int>(x.size());
  hash_boxes(h.vertices, vertex_box_of(x), 0, n);
  for (int i = 0; i < n; ++i)
    if (!is_surface(s, i)) h.vertices.cells[i] = {{0, 0, 0}, {-1, -1, -1}};
  hash_boxes(h.triangles, triangle_box_of(s, x), 0, static_cast<int>(s.tris.size()));
  hash_boxes(h.edges, edge_box_of(s, x), 0, static_cast<int>(s.edges.size()));
  hash_fill(h.vertices);
  hash_fill(h.triangles);
  hash_fill(h.edges);
}

inline void hash_query_vertices(const SelfContactLayout& s, const std::vector<ats_vec3>& x, const SurfaceHash& h,
                                float r, int begin, int end, PairLists& out) {
  for (int i = begin; i < end; ++i) {
    if (!is_surface(s, i)) continue;
    hash_walk(h.triangles, point_box(x[i], r), [&](int t) { test_vertex_triangle(s, x, i, t, r, out, true); });
  }
}

inline void hash_query_triangles(const SelfContactLayout& s, const std::vector<ats_vec3>& x, const SurfaceHash& h,
                                 float r, int begin, int end, PairLists& out) {
  for (int t = begin; t < end; ++t) {
    const auto& f = s.tris[t];
    hash_walk(h.vertices, triangle_box(x[f[0]], x[f[1]], x[f[2]], r),
              [&](int v) { test_vertex_triangle(s, x, v, t, r, out, false); });
  }
}

inline void hash_query_edges(const SelfContactLayout& s, const std::vector<ats_vec3>& x, const SurfaceHash& h, float r,
                             int begin, int end, PairLists& out) {
  for (int e = begin; e < end; ++e)
    hash_walk(h.edges, edge_box(x[s.edges[e][0]], x[s.edges[e][1]], r),
              [&](int f) { test_edge_edge(s, x, e, f, r, out); });
}

inline void hash_query(const SelfContactLayout& s, const std::vector<ats_vec3>& x, const SurfaceHash& h, float r,
                       PairLists& out) {
  hash_query_vertices(s, x, h, r, 0, static_cast<int>(x.size()), out);
  hash_query_triangles(s, x, h, r, 0, static_cast<int>(s.tris.size()), out);
  hash_query_edges(s, x, h, r, 0, static_cast<int>(s.edges.size()), out);
}

}  // namespace atssim::bench
