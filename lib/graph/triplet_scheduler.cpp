#include "graph/triplet_scheduler.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "graph/adjacency.hpp"
#include "graph/simd_batches.hpp"
#include "util/error.hpp"

namespace atssim::graph {

SimdBatches schedule_simd(std::span<const Triplet> triplets, int particle_count, int width) {
  const SimdOrder order = schedule_simd_order<3>(triplets, particle_count, width);
  SimdBatches out;
  out.set_sizes = order.set_sizes;
  const Triplet dummy = padding_dummy<3>(particle_count);
  for (int e : order.slots) {
    if (e >= 0) out.triplets.push_back(triplets[static_cast<std::size_t>(e)]);
    out.padded.push_back(e >= 0 ? triplets[static_cast<std::size_t>(e)] : dummy);
  }
  return out;
}

namespace {

// The bank counts of the warp being filled in one set.
struct OpenWarp {
  std::vector<int> conflicts;  // 3 slots x width banks
  std::array<int, 3> executions{0, 0, 0};
  int size = 0;
  int mark = -1;  // the triplet for which this set holds a neighbour
  explicit OpenWarp(int width) : conflicts(3 * static_cast<std::size_t>(width), 0) {}
};

}  // namespace

WarpSets schedule_warp(std::span<const Triplet> triplets, int particle_count, int width) {
  if (width < 1) throw internal_error(fmt::format("schedule_warp: width {} < 1", width));
  std::vector<int> flat;
  flat.reserve(3 * triplets.size());
  for (const Triplet& t : triplets) flat.insert(flat.end(), t.begin(), t.end());
  const Adjacency adjacency = build_adjacency(flat, 3, particle_count);
  int most = 0;
  for (int p = 0; p < particle_count; ++p) most = std::max(most, static_cast<int>(adjacency.of(p).size()));

  std::vector<OpenWarp> sets(static_cast<std::size_t>(most), OpenWarp(width));
  std::vector<int> sizes(static_cast<std::size_t>(most), 0);
  std::vector<int> set_of(triplets.size(), -1);
  WarpSets out;
  for (std::size_t ti = 0; ti < triplets.size(); ++ti) {
    const Triplet& t = triplets[ti];
    const int mark = static_cast<int>(ti);
    for (int p : t) {
      for (int other : adjacency.of(p)) {
        if (set_of[other] >= 0) sets[set_of[other]].mark = mark;
      }
    }
    // The set without a neighbour where t adds the fewest executions.
    int best = -1, best_added = 4;
    for (std::size_t s = 0; s < sets.size() && best_added > 0; ++s) {
      const OpenWarp& w = sets[s];
      if (w.mark == mark) continue;
      int added = 0;
      for (int k = 0; k < 3; ++k) {
        // As NvCloth counts: a read costs an extra execution only on a bank
        // that is already the busiest (an empty warp costs none: 1 anyway).
        const int count = w.conflicts[k * width + t[k] % width];
        added += count == std::max(1, w.executions[k]) ? 1 : 0;
      }
      if (added < best_added) {
        best_added = added;
        best = static_cast<int>(s);
      }
    }
    if (best < 0) {
      sets.emplace_back(width);
      sizes.push_back(0);
      best = static_cast<int>(sets.size()) - 1;
    }
    OpenWarp& w = sets[best];
    for (int k = 0; k < 3; ++k) {
      int& count = w.conflicts[k * width + t[k] % width];
      w.executions[k] = std::max(w.executions[k], ++count);
    }
    set_of[ti] = best;
    ++sizes[best];
    if (++w.size == width) {  // the warp is full: count it, start the next one
      out.replays += w.executions[0] + w.executions[1] + w.executions[2];
      const int m = w.mark;
      w = OpenWarp(width);
      w.mark = m;
    }
  }
  for (const OpenWarp& w : sets) out.replays += w.executions[0] + w.executions[1] + w.executions[2];
  // Sets one after another, insertion order inside each.
  std::vector<int> offset(sizes.size() + 1, 0);
  for (std::size_t s = 0; s < sizes.size(); ++s) offset[s + 1] = offset[s] + sizes[s];
  out.triplets.resize(triplets.size());
  for (std::size_t ti = 0; ti < triplets.size(); ++ti) out.triplets[offset[set_of[ti]]++] = triplets[ti];
  for (int s : sizes) {
    if (s > 0) out.set_sizes.push_back(s);
  }
  return out;
}

long long bank_replays(std::span<const Triplet> triplets, std::span<const int> set_sizes, int width) {
  long long total = 0;
  std::size_t first = 0;
  for (int size : set_sizes) {
    for (int start = 0; start < size; start += width) {
      const int end = std::min(size, start + width);
      for (int k = 0; k < 3; ++k) {
        int worst = 0;
        for (int bank = 0; bank < width; ++bank) {
          int count = 0;
          for (int i = start; i < end; ++i) count += triplets[first + i][k] % width == bank ? 1 : 0;
          worst = std::max(worst, count);
        }
        total += worst;
      }
    }
    first += static_cast<std::size_t>(size);
  }
  return total;
}

}  // namespace atssim::graph
