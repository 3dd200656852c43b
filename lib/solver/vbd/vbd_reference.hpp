#pragma once
// Host reference implementation of the VBD substep (Chen et al. 2024): the
// tasks of make_vbd_plan in its order (predict; per iteration the vertex
// colors in order, then the ground; the velocity update), each vertex step
// from the same gather and 3x3 solve as the kernel (kernels/common/
// vertex_system.h, vertex_solve.h). With threads > 1 each color's vertices
// run as a tbb::parallel_for, the native multi-threaded loop that atssim's
// devices are compared with (bench/bench_native.cpp); vertices of one color
// share no element, so the result is bit-identical to 1 thread. lanes: each
// color's vertices in batches of 8 whose gather runs as 8-float vectors (GCC
// vector extensions, kernels/common/vertex_system_lanes.h), as the
// color_batches ordering's kernel does: the same bits, the native loop of that
// ordering.
#include <memory>
#include <vector>

#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_layout.hpp"

namespace atssim::solver::vbd {

class VbdReference {
 public:
  // threads: 1 runs plain loops; more run the particle loops and each vertex
  // color in a tbb::task_arena of that many threads. Throws atssim::Error
  // (input) when a constraint is infinitely stiff, as make_vbd_plan does.
  VbdReference(SimLayout layout, double substep_dt, int iterations, int threads = 1, bool lanes = false);
  VbdReference(VbdReference&&) noexcept;
  VbdReference& operator=(VbdReference&&) noexcept;
  ~VbdReference();

  void substep();
  const SimLayout& state() const { return layout_; }
  // x~ of the last substep: the inertia target, and the first guess.
  const std::vector<Float4>& predicted() const { return x_tilde_; }

 private:
  void substep_here();  // the substep, in the arena already when threads > 1
  void predict();
  void solve_color(int color);
  void solve_color_lanes(int color);
  void project_ground();
  void update_velocity();
  // body(i) for i in [first, last): in order, or in parallel in the arena.
  template <class Body>
  void sweep(int first, int last, const Body& body);

  SimLayout layout_;
  vertex::VertexLayout vertices_;
  vertex::ColorLanes lanes_;  // empty: one vertex at a time
  double substep_dt_;
  int iterations_;
  float damping_inv_h_ = 0.0f;  // 1/h when a spring is damped (add_spring_damping), else 0
  std::vector<Float4> x_prev_;
  std::vector<Float4> x_tilde_;
  struct Arena;                   // a tbb::task_arena, kept out of this header
  std::unique_ptr<Arena> arena_;  // null: 1 thread
};

}  // namespace atssim::solver::vbd
