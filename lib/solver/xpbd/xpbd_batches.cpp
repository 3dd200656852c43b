#include "solver/xpbd/xpbd_batches.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <utility>

#include "graph/simd_batches.hpp"

namespace atssim::solver::xpbd {

namespace {

std::array<int, 2> particles(const ats_distance_c& c) { return {c.a, c.b}; }
std::array<int, 4> particles(const ats_bend_c& c) { return {c.v[0], c.v[1], c.v[2], c.v[3]}; }
std::array<int, 4> particles(const ats_tet_c& c) { return {c.v[0], c.v[1], c.v[2], c.v[3]}; }

void set_particles(ats_distance_c& c, const std::array<int, 2>& p) {
  c.a = p[0];
  c.b = p[1];
}
template <class Stencil>
void set_particles(Stencil& c, const std::array<int, 4>& p) {
  for (int k = 0; k < 4; ++k) c.v[k] = p[static_cast<std::size_t>(k)];
}

// The greedy batching runs over the elements in particle order (each keyed
// by its particles, smallest first), as NvCloth's over mesh order: over the
// layout's color-sorted order it would take each color block's elements in
// turn and reproduce the color order almost exactly.
template <class Element>
ElementBatches<Element> batch(const std::vector<Element>& set, int particle_count) {
  using Tuple = decltype(particles(set.front()));
  std::vector<Tuple> keys;
  keys.reserve(set.size());
  for (const Element& e : set) {
    Tuple k = particles(e);
    std::sort(k.begin(), k.end());
    keys.push_back(k);
  }
  std::vector<int> by_particles(set.size());
  std::iota(by_particles.begin(), by_particles.end(), 0);
  std::stable_sort(by_particles.begin(), by_particles.end(),
                   [&](int a, int b) { return keys[static_cast<std::size_t>(a)] < keys[static_cast<std::size_t>(b)]; });
  std::vector<Tuple> tuples;
  tuples.reserve(set.size());
  for (int e : by_particles) tuples.push_back(particles(set[static_cast<std::size_t>(e)]));
  ElementBatches<Element> out;
  out.source = graph::schedule_simd_order<std::tuple_size_v<Tuple>>(tuples, particle_count, kBatchWidth).slots;
  for (int& s : out.source) {
    if (s >= 0) s = by_particles[static_cast<std::size_t>(s)];
  }
  Element dummy{};
  set_particles(dummy, graph::padding_dummy<std::tuple_size_v<Tuple>>(particle_count));
  out.elements.reserve(out.source.size());
  for (int e : out.source) out.elements.push_back(e >= 0 ? set[static_cast<std::size_t>(e)] : dummy);
  return out;
}

template <class Element>
void as_one_block(std::vector<Element>& set, std::vector<int>& blocks, int particle_count) {
  const ElementBatches<Element> b = batch(set, particle_count);
  std::vector<Element> swept;
  swept.reserve(set.size());
  for (std::size_t k = 0; k < b.source.size(); ++k) {
    if (b.source[k] >= 0) swept.push_back(b.elements[k]);
  }
  set = std::move(swept);
  blocks = {0, static_cast<int>(set.size())};
}

template <class Element>
ColorBatches<Element> cut_blocks(const std::vector<Element>& set, const std::vector<int>& blocks, int particle_count) {
  using Tuple = decltype(particles(set.front()));
  Element dummy{};
  set_particles(dummy, graph::padding_dummy<std::tuple_size_v<Tuple>>(particle_count));
  ColorBatches<Element> out;
  out.blocks.push_back(0);
  for (std::size_t b = 0; b + 1 < blocks.size(); ++b) {
    for (int e = blocks[b]; e < blocks[b + 1]; ++e) {
      out.set.source.push_back(e);
      out.set.elements.push_back(set[static_cast<std::size_t>(e)]);
    }
    while (out.set.source.size() % kBatchWidth != 0) {
      out.set.source.push_back(-1);
      out.set.elements.push_back(dummy);
    }
    out.blocks.push_back(out.set.batches());
  }
  return out;
}

}  // namespace

ColorBatches<ats_distance_c> color_batches(const std::vector<ats_distance_c>& stretch, const std::vector<int>& blocks,
                                           int particle_count) {
  return cut_blocks(stretch, blocks, particle_count);
}

ColorBatches<ats_bend_c> color_batches(const std::vector<ats_bend_c>& bend, const std::vector<int>& blocks,
                                       int particle_count) {
  return cut_blocks(bend, blocks, particle_count);
}

ColorBatches<ats_tet_c> color_batches(const std::vector<ats_tet_c>& tets, const std::vector<int>& blocks,
                                      int particle_count) {
  return cut_blocks(tets, blocks, particle_count);
}

SimLayout in_batch_order(SimLayout layout) {
  const int n = static_cast<int>(layout.x.size());
  if (!layout.stretch.empty()) as_one_block(layout.stretch, layout.stretch_blocks, n);
  if (!layout.bend.empty()) as_one_block(layout.bend, layout.bend_blocks, n);
  if (!layout.tets.empty()) as_one_block(layout.tets, layout.tet_blocks, n);
  return layout;
}

ElementBatches<ats_distance_c> batch_elements(const std::vector<ats_distance_c>& stretch, int particle_count) {
  return batch(stretch, particle_count);
}

ElementBatches<ats_bend_c> batch_elements(const std::vector<ats_bend_c>& bend, int particle_count) {
  return batch(bend, particle_count);
}

ElementBatches<ats_tet_c> batch_elements(const std::vector<ats_tet_c>& tets, int particle_count) {
  return batch(tets, particle_count);
}

}  // namespace atssim::solver::xpbd
