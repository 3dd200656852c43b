#pragma once
// Host reference of explicit integration (seed 001 Eqs. 2-4): the same
// per-particle force gather as the kernels (kernels/common/vertex_force.h)
// and the integrators' stages as plain loops over the particles, or each
// loop as a tbb::parallel_for in an arena of N threads: the native loop a
// user would write instead of atssim (bench/bench_native.cpp, issue #13's
// seed-001 comparison).
#include <memory>
#include <vector>

#include "solver/explicit/explicit_plan.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_layout.hpp"

namespace atssim::solver::explicit_rk {

class ExplicitReference {
 public:
  ExplicitReference(SimLayout layout, ExplicitSettings settings, int threads = 1);
  ExplicitReference(ExplicitReference&&) noexcept;
  ExplicitReference& operator=(ExplicitReference&&) noexcept;
  ~ExplicitReference();

  void substep();
  const SimLayout& state() const { return layout_; }

 private:
  // accel_ = a(xs, vs) for every particle.
  void forces(const std::vector<Float4>& xs, const std::vector<Float4>& vs);
  template <class Body>
  void sweep(const Body& body);

  SimLayout layout_;
  ExplicitSettings settings_;
  vertex::VertexLayout vertices_;
  std::vector<Float4> xs_, vs_, accel_, sum_x_, sum_v_;
  struct Arena;
  std::unique_ptr<Arena> arena_;  // null: 1 thread
};

}  // namespace atssim::solver::explicit_rk
