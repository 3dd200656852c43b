#pragma once
// solver.ordering: batches. An XPBD element set reordered into NvCloth's
// simd batches (graph/simd_batches): batches of ATS_XPBD_BATCH_WIDTH
// elements that share no particle, each set padded with the dummy whose
// particles lie past the last one (the kernels skip it). One task sweeps the
// padded set batch after batch (kernels/xpbd/xpbd.cl, *_batches).
#include <vector>

#include "common/element_types.h"
#include "common/xpbd_batches.h"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::xpbd {

inline constexpr int kBatchWidth = ATS_XPBD_BATCH_WIDTH;

template <class Element>
struct ElementBatches {
  std::vector<Element> elements;  // padded: batches() * kBatchWidth elements
  std::vector<int> source;        // per slot, the index in the input set, -1 = dummy
  int batches() const { return static_cast<int>(elements.size()) / kBatchWidth; }
};

ElementBatches<ats_distance_c> batch_elements(const std::vector<ats_distance_c>& stretch, int particle_count);
ElementBatches<ats_bend_c> batch_elements(const std::vector<ats_bend_c>& bend, int particle_count);
ElementBatches<ats_tet_c> batch_elements(const std::vector<ats_tet_c>& tets, int particle_count);

// solver.ordering: color_batches. Each color block of a set (`blocks`, its
// element offsets) cut into consecutive batches of kBatchWidth, the last
// batch of a block padded with the dummy. The elements of one block share no
// particle, so any kBatchWidth of them are a batch, and the batches of one
// block are independent: a block is a range of batches that split and heft
// cut like a color block (kernels/xpbd/xpbd.cl, *_lanes). The order of the
// updates is the color order's, so only the float rounding of the lanes can
// tell the two apart.
template <class Element>
struct ColorBatches {
  ElementBatches<Element> set;  // padded per block; source as above
  std::vector<int> blocks;      // batch offsets of the blocks: blocks.size() = blocks in + 1
};

ColorBatches<ats_distance_c> color_batches(const std::vector<ats_distance_c>& stretch, const std::vector<int>& blocks,
                                           int particle_count);
ColorBatches<ats_bend_c> color_batches(const std::vector<ats_bend_c>& bend, const std::vector<int>& blocks,
                                       int particle_count);
ColorBatches<ats_tet_c> color_batches(const std::vector<ats_tet_c>& tets, const std::vector<int>& blocks,
                                      int particle_count);

// `layout` with its stretch, bending and tet sets in the batches' sweep order
// (dummies left out), each one color block: the host reference's serial loop
// over it visits the constraints in the order the batches task sweeps them
// (for its tests and bench/bench_native --ordering batches; one thread only).
SimLayout in_batch_order(SimLayout layout);

}  // namespace atssim::solver::xpbd
