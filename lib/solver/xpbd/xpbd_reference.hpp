#pragma once
// Host reference implementation of the XPBD substep, on the same layout and
// the same element math headers as the kernels; the OpenCL result is tested
// against it. With threads > 1 each color block runs as a tbb::parallel_for,
// the native multi-threaded loop that atssim's devices are compared with
// (bench/bench_native.cpp); the result is bit-identical to 1 thread.
#include <memory>
#include <vector>

#include "solver/layout/sim_layout.hpp"
#include "solver/xpbd/xpbd_plan.hpp"

namespace atssim::solver::xpbd {

class XpbdReference {
 public:
  // threads: 1 runs plain loops; more run the particle loops and each color
  // block in a tbb::task_arena of that many threads.
  XpbdReference(SimLayout layout, XpbdSettings settings, int threads = 1);
  XpbdReference(XpbdReference&&) noexcept;
  XpbdReference& operator=(XpbdReference&&) noexcept;
  ~XpbdReference();

  void substep();
  const SimLayout& state() const { return layout_; }

  // Root mean square of the XPBD residual C(x) + alpha~ lambda over all
  // stretch constraints (and each bending component and tet strain
  // constraint), after the last substep.
  double residual_rms() const;

 private:
  void substep_here();  // the substep, in the arena already when threads > 1
  void predict();
  void solve_stretch(bool reset);
  void solve_bend(bool reset);
  void solve_tets(bool reset);
  void project_ground();
  void update_velocity();
  // body(i) for i in [first, last): in order, or in parallel in the arena.
  template <class Body>
  void sweep(int first, int last, const Body& body);

  SimLayout layout_;
  XpbdSettings settings_;
  std::vector<Float4> x_prev_;
  std::vector<float> stretch_lambda_;
  std::vector<float> bend_lambda_;  // 3 per stencil
  std::vector<float> tet_lambda_;   // ATS_TET_LAMBDA_STRIDE per tet
  float inv_h_;                     // 1/h with damped springs, else 0 (xpbd_stretch's inv_h)
  struct Arena;                     // a tbb::task_arena, kept out of this header
  std::unique_ptr<Arena> arena_;    // null: 1 thread
};

}  // namespace atssim::solver::xpbd
