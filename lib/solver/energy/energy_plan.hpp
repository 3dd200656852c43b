#pragma once
// The incremental potential's terms on a device: a plan for program
// "xpbd_energy" (kernels/xpbd/xpbd_energy.cl) with one task, "energy", whose
// launches write one float per particle (inertia) and per constraint into the
// buffer `energy`; the caller sums them. device::PlanExecutor runs it like
// any substep plan; to evaluate another state, write it into `x` and run the
// plan again.
#include <vector>

#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::energy {

// Buffer ids inside an energy plan (those absent from the layout are -1).
struct EnergyBuffers {
  plan::BufferId x = -1, predicted = -1, stretch = -1, bend = -1, tets = -1, energy = -1;
};

// Where each term lands in the output array: particles, then stretch
// constraints, then bending stencils, then tets, each in layout order.
struct EnergyOutput {
  int inertia_first = 0;
  int stretch_first = 0;
  int bend_first = 0;
  int tet_first = 0;
  int size = 0;
};

EnergyOutput energy_output(const SimLayout& layout);

// Throws atssim::Error (input) when a constraint has compliance 0 (no finite
// energy), a tet has mu <= 0 or lambda < 0, or predicted and the layout
// differ in size.
plan::SubstepPlan make_energy_plan(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                                   EnergyBuffers* ids = nullptr);

}  // namespace atssim::solver::energy
