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

// `layout` with its stretch and bending sets in the batches' sweep order
// (dummies left out), each one color block: the host reference's serial loop
// over it visits the constraints in the order the batches task sweeps them
// (for its tests and bench/bench_native --ordering batches; one thread only).
SimLayout in_batch_order(SimLayout layout);

}  // namespace atssim::solver::xpbd
