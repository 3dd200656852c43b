#pragma once
// Host reference implementation of the XPBD substep, on the same layout and
// the same element math headers as the kernels; the OpenCL result is tested
// against it.
#include <vector>

#include "solver/layout/sim_layout.hpp"
#include "solver/xpbd/xpbd_plan.hpp"

namespace atssim::solver::xpbd {

class XpbdReference {
 public:
  XpbdReference(SimLayout layout, XpbdSettings settings);

  void substep();
  const SimLayout& state() const { return layout_; }

  // Root mean square of the XPBD residual C(x) + alpha~ lambda over all
  // stretch constraints (and each bending component and tet strain
  // constraint), after the last substep.
  double residual_rms() const;

 private:
  void predict();
  void solve_stretch(bool reset);
  void solve_bend(bool reset);
  void solve_tets(bool reset);
  void update_velocity();

  SimLayout layout_;
  XpbdSettings settings_;
  std::vector<Float4> x_prev_;
  std::vector<float> stretch_lambda_;
  std::vector<float> bend_lambda_;  // 3 per stencil
  std::vector<float> tet_lambda_;   // ATS_TET_LAMBDA_STRIDE per tet
};

}  // namespace atssim::solver::xpbd
