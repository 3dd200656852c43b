#include "solver/xpbd/xpbd_plan.hpp"

#include <cstring>

#include <fmt/format.h>

#include "common/xpbd_tet.h"
#include "solver/collision_tasks.hpp"

#include "util/error.hpp"

namespace atssim::solver::xpbd {

namespace {

using Arg = KernelArg;

// Adds one task per color block of one element set, chained after `last`.
sched::TaskId add_blocks(SubstepPlan& plan, sched::TaskId last, const std::vector<int>& blocks,
                         const std::string& kind, const std::string& kernel, BufferId x, BufferId elements,
                         BufferId lambda, float dt, int iteration) {
  for (int b = 0; b + 1 < static_cast<int>(blocks.size()); ++b) {
    const int first = blocks[b];
    const int count = blocks[b + 1] - blocks[b];
    KernelLaunch launch{kernel, static_cast<std::size_t>(count),
                        {Arg::of_buffer(x), Arg::of_buffer(elements), Arg::of_buffer(lambda), Arg::of_int(first),
                         Arg::of_int(count), Arg::of_float(dt), Arg::of_int(iteration == 0 ? 1 : 0)},
                        3};
    const sched::TaskId id =
        plan.add_task({fmt::format("it{}/{}/c{}", iteration + 1, kind, b), kind, iteration, b}, {launch});
    plan.graph.add_edge(last, id);
    last = id;
  }
  return last;
}

// The strain constraints (common/xpbd_tet.h) minimise the StVK energy; solving
// them for a neo-Hookean solid would silently change its material.
void check_tets_are_stvk(const SimLayout& layout) {
  for (const ats_tet_c& t : layout.tets) {
    if (t.model != ATS_TET_STVK) {
      throw input_error("solver.method xpbd simulates solids with material model: stvk only (its strain "
                        "constraints are the StVK energy); set the solid's material.model to stvk, or use "
                        "solver.method vbd, sosd or jpgd for neo_hookean");
    }
  }
}

}  // namespace

SubstepPlan make_xpbd_plan(const SimLayout& layout, const XpbdSettings& settings, XpbdBuffers* ids) {
  SubstepPlan plan;
  plan.program = "xpbd";
  plan.particle_count = static_cast<int>(layout.x.size());
  XpbdBuffers b;
  b.x = plan.add_buffer("x", bytes_of(layout.x));
  b.v = plan.add_buffer("v", bytes_of(layout.v));
  b.x_prev = plan.add_buffer("x_prev", bytes_of(layout.x));
  if (!layout.stretch.empty()) {
    b.stretch = plan.add_buffer("stretch", bytes_of(layout.stretch));
    b.stretch_lambda = plan.add_buffer("stretch_lambda", std::vector<std::byte>(layout.stretch.size() * sizeof(float)));
  }
  if (!layout.bend.empty()) {
    b.bend = plan.add_buffer("bend", bytes_of(layout.bend));
    b.bend_lambda = plan.add_buffer("bend_lambda", std::vector<std::byte>(layout.bend.size() * 4 * sizeof(float)));
  }
  if (!layout.tets.empty()) {
    check_tets_are_stvk(layout);
    b.tet = plan.add_buffer("tet", bytes_of(layout.tets));
    b.tet_lambda =
        plan.add_buffer("tet_lambda", std::vector<std::byte>(layout.tets.size() * ATS_TET_LAMBDA_STRIDE * sizeof(float)));
  }
  plan.positions = b.x;

  const float dt = static_cast<float>(settings.substep_dt);
  const int n = plan.particle_count;
  const std::size_t global = static_cast<std::size_t>(n);
  sched::TaskId last = plan.add_task(
      {"predict", "predict", -1, -1},
      {{"xpbd_predict", global,
        {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev), Arg::of_float(dt),
         Arg::of_float(layout.gravity.x), Arg::of_float(layout.gravity.y), Arg::of_float(layout.gravity.z),
         Arg::of_int(0), Arg::of_int(n)},
        7}});
  for (int it = 0; it < settings.iterations; ++it) {
    if (b.stretch >= 0) {
      last = add_blocks(plan, last, layout.stretch_blocks, "stretch", "xpbd_stretch", b.x, b.stretch,
                        b.stretch_lambda, dt, it);
    }
    if (b.bend >= 0) {
      last = add_blocks(plan, last, layout.bend_blocks, "bend", "xpbd_bend", b.x, b.bend, b.bend_lambda, dt, it);
    }
    if (b.tet >= 0) {
      last = add_blocks(plan, last, layout.tet_blocks, "tet", "xpbd_tet", b.x, b.tet, b.tet_lambda, dt, it);
    }
    last = add_ground_task(plan, last, layout, b.x, it);
  }
  const sched::TaskId update = plan.add_task(
      {"update_velocity", "update_velocity", -1, -1},
      {{"particles_update_velocity", global,
        {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev), Arg::of_float(1.0f / dt),
         Arg::of_int(0), Arg::of_int(n)},
        4}});
  plan.graph.add_edge(last, update);
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::xpbd
