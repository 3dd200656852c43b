#pragma once
// solver.ordering: batches on the host, for bench_native --ordering batches
// (docs/benchmarks.md, "Native loops"): the padded sets of
// solver/xpbd/xpbd_batches swept batch after batch, the 8 lanes of a batch
// as one 8-float vector (GCC vector extensions; one AVX register under
// -march=native), the operations of kernels/xpbd/xpbd.cl's
// xpbd_stretch_batch8 and xpbd_bend_batch8 (bench/float8_lanes.hpp). A batch
// with a damped spring or a dihedral stencil runs its lanes one after another
// with the scalar math, as the kernels do. One thread: consecutive batches
// share particles, so a set's sweep is one Gauss–Seidel chain (on the device,
// too, one task sweeps a set); there is nothing for a parallel_for to split.
// (bench/plain_xpbd_color_batches.hpp: batches cut from the color blocks,
// which can.)
#include <vector>

#include "float8_lanes.hpp"
#include "plain_xpbd.hpp"
#include "solver/xpbd/xpbd_batches.hpp"

namespace atssim::bench {

class PlainXpbdBatches : public PlainParticles {
  using Stretch = solver::xpbd::ElementBatches<ats_distance_c>;
  using Bend = solver::xpbd::ElementBatches<ats_bend_c>;

 public:
  PlainXpbdBatches(const solver::SimLayout& layout, double h, int iterations)
      : PlainParticles(layout, h),
        n_(static_cast<int>(layout.x.size())),
        stretch_(layout.stretch.empty() ? Stretch{} : solver::xpbd::batch_elements(layout.stretch, n_)),
        bend_(layout.bend.empty() ? Bend{} : solver::xpbd::batch_elements(layout.bend, n_)),
        stretch_lambda_(stretch_.elements.size()),
        bend_lambda_(bend_.elements.size() * 3),
        iterations_(iterations),
        inertia_dt_(static_cast<float>(solver::inertia_dt(layout, h))),
        inv_h_(solver::has_spring_damping(layout) ? 1.0f / static_cast<float>(h) : 0.0f) {
    static_assert(solver::xpbd::kBatchWidth == 8, "the lanes below are 8 floats");
    if (!layout.tets.empty())
      throw input_error("bench_native --ordering batches: cloth only (the scene has tetrahedra)");
  }

  void substep() {
    predict(false);
    for (int it = 0; it < iterations_; ++it) {
      const bool reset = it == 0;
      for (int b = 0; b < stretch_.batches(); ++b) stretch_batch(8 * b, reset);
      for (int b = 0; b < bend_.batches(); ++b) bend_batch(8 * b, reset);
      ground(false);
    }
    update_velocity(false);
  }

 private:
  void stretch_batch(int k0, bool reset) {
    lanes::stretch_group8(x_.data(), x_prev_.data(), stretch_.elements.data() + k0, stretch_lambda_.data() + k0, n_,
                          inertia_dt_, inv_h_, reset);
  }
  void bend_batch(int k0, bool reset) {
    lanes::bend_group8(x_.data(), bend_.elements.data() + k0, bend_lambda_.data() + 3 * k0, n_, inertia_dt_, reset);
  }

  int n_;
  Stretch stretch_;
  Bend bend_;
  std::vector<float> stretch_lambda_, bend_lambda_;
  int iterations_;
  float inertia_dt_, inv_h_;
};

}  // namespace atssim::bench
