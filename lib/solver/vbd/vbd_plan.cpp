#include "solver/vbd/vbd_plan.hpp"

#include <fmt/format.h>

#include "solver/collision_tasks.hpp"
#include "solver/layout/particle_tables.hpp"
#include "solver/self_contact_tasks.hpp"

namespace atssim::solver::vbd {

plan::SubstepPlan make_vbd_plan(const SimLayout& layout, double substep_dt, int iterations,
                                vertex::VertexBuffers* ids) {
  const vertex::VertexLayout vertices = vertex::make_vertex_layout(layout);
  plan::SubstepPlan plan;
  plan.program = "vbd";
  vertex::VertexBuffers b;
  sched::TaskId last = vertex::begin_vertex_plan(plan, layout, vertices, substep_dt, b);
  const double hi = inertia_dt(layout, substep_dt);  // air drag weighs the inertia (sim_layout.hpp)
  const SelfContactBuffers sc = add_self_contact_buffers(plan, layout);
  last = add_self_contact_detection(plan, last, layout, sc, b.x_prev, b.x);
  const float inv_h2 = static_cast<float>(1.0 / (hi * hi));
  // Element k of a color writes particle order[k].
  const auto order =
      std::make_shared<const std::vector<std::int32_t>>(vertices.colors.order.begin(), vertices.colors.order.end());
  for (int it = 0; it < iterations; ++it) {
    for (int c = 0; c < vertices.colors.count(); ++c) {
      const int first = vertices.colors.offsets[c];
      const int count = vertices.colors.offsets[c + 1] - first;
      using Arg = plan::KernelArg;
      std::vector<Arg> args{Arg::of_buffer(b.x),
                            Arg::of_buffer(b.x_tilde),
                            Arg::of_buffer(b.adjacency_offsets),
                            Arg::of_buffer(b.adjacency),
                            Arg::of_buffer(b.stretch),
                            Arg::of_buffer(b.bend),
                            Arg::of_buffer(b.tets),
                            Arg::of_buffer(b.order),
                            Arg::of_float(inv_h2),
                            Arg::of_int(layout.has_ground ? 1 : 0),
                            Arg::of_float(layout.ground_y)};
      for (const Arg& a : vertex::collider_args(layout, b)) args.push_back(a);
      for (const Arg& a : vertex::damping_args(layout, b, substep_dt)) args.push_back(a);
      for (const Arg& a : self_contact_args(layout, sc, hi)) args.push_back(a);
      last = plan.add_task_after(
          last, plan::make_task(fmt::format("it{}/vertex/c{}", it + 1, c), plan::TaskKind::vertex, it, c),
          {"vbd_solve", {first, count}, std::move(args), {plan::WriteSpan::per_index(b.x, kParticleBytes, 1, order)}});
    }
    last = add_ground_task(plan, last, layout, b.x, it);
  }
  last = add_self_contact_friction(plan, last, layout, sc, b.x_prev, b.x, b.v, substep_dt);
  vertex::end_vertex_plan(plan, layout, last, b, substep_dt);
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::vbd
