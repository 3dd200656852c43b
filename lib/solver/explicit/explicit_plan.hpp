#pragma once
// The substep of explicit integration (seed 001, Eqs. 2-4): per force
// evaluation one `forces` task (every particle's acceleration gathered over
// its elements, kernels/common/vertex_force.h) and one `integrate` task (the
// integrator's stage), each a launch over the particle range, so split and
// heft cut every stage between devices with one synchronisation each and the
// one-device result. Semi-implicit Euler: 1 evaluation; midpoint: 2; RK4: 4.
#include <string_view>

#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_layout.hpp"

namespace atssim::solver::explicit_rk {

// The embedded program its plans run: kernels/explicit/explicit.cl.
inline constexpr std::string_view kProgram = "explicit";

enum class Integrator { semi_euler, midpoint, rk4 };

inline constexpr std::string_view kIntegratorNames[] = {"semi_euler", "midpoint", "rk4"};

// Force evaluations per step.
int evaluations(Integrator integrator);

struct ExplicitSettings {
  double substep_dt = 1.0 / 960.0;
  Integrator integrator = Integrator::semi_euler;
};

struct ExplicitBuffers {
  plan::BufferId x = -1, v = -1, xs = -1, vs = -1, a = -1, sum_x = -1, sum_v = -1, stretch = -1, bend = -1, tets = -1,
                 adjacency_offsets = -1, adjacency = -1;
};

plan::SubstepPlan make_explicit_plan(const SimLayout& layout, const ExplicitSettings& settings,
                                     ExplicitBuffers* ids = nullptr);

}  // namespace atssim::solver::explicit_rk
