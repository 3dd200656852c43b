#include "solver/vertex/vertex_plan.hpp"

#include "solver/energy/finite_stiffness.hpp"
#include "solver/layout/particle_tables.hpp"

namespace atssim::solver::vertex {

using Arg = plan::KernelArg;

sched::TaskId begin_vertex_plan(plan::SubstepPlan& plan, const SimLayout& layout, const VertexLayout& vertices,
                                double substep_dt, VertexBuffers& b) {
  energy::require_finite_stiffness(layout);
  const int n = static_cast<int>(layout.x.size());
  plan.particle_count = n;
  using plan::BufferRole;
  b.x = plan.add_buffer("x", BufferRole::positions, plan::bytes_of(layout.x));
  b.v = plan.add_buffer("v", BufferRole::velocities, plan::bytes_of(layout.v));
  b.x_prev = plan.add_buffer("x_prev", BufferRole::start_positions, plan::bytes_of(layout.x));
  b.x_tilde = plan.add_buffer("x_tilde", BufferRole::inertia_target, plan::bytes_of(layout.x));
  b.stretch = plan.add_buffer("stretch", BufferRole::elements, plan::bytes_of(layout.stretch));
  b.bend = plan.add_buffer("bend", BufferRole::elements, plan::bytes_of(layout.bend));
  b.tets = plan.add_buffer("tets", BufferRole::elements, plan::bytes_of(layout.tets));
  b.adjacency_offsets =
      plan.add_buffer("adjacency_offsets", BufferRole::topology, plan::bytes_of(vertices.adjacency_offsets));
  b.adjacency = plan.add_buffer("adjacency", BufferRole::topology, plan::bytes_of(vertices.adjacency));
  b.order = plan.add_buffer("vertex_order", BufferRole::topology, plan::bytes_of(vertices.colors.order));
  const float dt = static_cast<float>(substep_dt);
  return plan.add_task(
      plan::make_task("predict", plan::TaskKind::predict),
      {{"particles_predict",
        {0, n},
        {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev), Arg::of_buffer(b.x_tilde),
         Arg::of_float(dt), Arg::of_float(layout.gravity.x), Arg::of_float(layout.gravity.y),
         Arg::of_float(layout.gravity.z), Arg::of_float(velocity_damping(layout, substep_dt))},
        {particle_write(b.x), particle_write(b.v), particle_write(b.x_prev), particle_write(b.x_tilde)}}});
}

void end_vertex_plan(plan::SubstepPlan& plan, sched::TaskId last, const VertexBuffers& b, double substep_dt) {
  const int n = plan.particle_count;
  plan.add_task_after(last, plan::make_task("update_velocity", plan::TaskKind::update_velocity),
                      {"particles_update_velocity",
                       {0, n},
                       {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev),
                        Arg::of_float(static_cast<float>(1.0 / substep_dt))},
                       {particle_write(b.v)}});
}

}  // namespace atssim::solver::vertex
