#include "solver/vertex/vertex_plan.hpp"

#include "solver/collision_tasks.hpp"
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
  b.colliders = add_collider_buffers(plan, layout);
  b.friction = add_friction_buffer(plan, layout);
  const float dt = static_cast<float>(substep_dt);
  const sched::TaskId predict = plan.add_task(
      plan::make_task("predict", plan::TaskKind::predict),
      {{"particles_predict",
        {0, n},
        {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev), Arg::of_buffer(b.x_tilde),
         Arg::of_float(dt), Arg::of_float(layout.gravity.x), Arg::of_float(layout.gravity.y),
         Arg::of_float(layout.gravity.z), Arg::of_float(velocity_damping(layout, substep_dt))},
        {particle_write(b.x), particle_write(b.v), particle_write(b.x_prev), particle_write(b.x_tilde)}}});
  return add_collider_near_task(plan, predict, layout, b.colliders, b.x);
}

std::vector<plan::KernelArg> collider_args(const SimLayout& layout, const VertexBuffers& b) {
  return solver::collider_args(layout, b.colliders);
}

std::vector<plan::KernelArg> damping_args(const SimLayout& layout, const VertexBuffers& b, double substep_dt) {
  return {Arg::of_buffer(b.x_prev),
          Arg::of_float(has_spring_damping(layout) ? static_cast<float>(1.0 / substep_dt) : 0.0f)};
}

void end_vertex_plan(plan::SubstepPlan& plan, const SimLayout& layout, sched::TaskId last, const VertexBuffers& b,
                     double substep_dt) {
  const int n = plan.particle_count;
  if (!layout.colliders.empty()) {
    // Friction from x into a scratch copy, then back: a vertex's normal force
    // needs its neighbours' positions before their friction step.
    const plan::BufferId out = plan.add_buffer("x_friction", plan::BufferRole::scratch,
                                               std::vector<std::byte>(static_cast<std::size_t>(n) * kParticleBytes));
    last = plan.add_task_after(
        last, plan::make_task("friction", plan::TaskKind::friction),
        {"vertex_friction",
         {0, n},
         with_colliders(
             {Arg::of_buffer(b.x), Arg::of_buffer(out), Arg::of_buffer(b.x_prev), Arg::of_buffer(b.x_tilde),
              Arg::of_buffer(b.adjacency_offsets), Arg::of_buffer(b.adjacency), Arg::of_buffer(b.stretch),
              Arg::of_buffer(b.bend), Arg::of_buffer(b.tets)},
             layout, b.colliders,
             {Arg::of_float(static_cast<float>(1.0 / (substep_dt * substep_dt))), Arg::of_buffer(b.friction)}),
         {particle_write(out)}});
    last = plan.add_task_after(
        last, plan::make_task("friction_copy", plan::TaskKind::copy),
        {"particles_copy", {0, n}, {Arg::of_buffer(b.x), Arg::of_buffer(out)}, {particle_write(b.x)}});
  }
  plan.add_task_after(last, plan::make_task("update_velocity", plan::TaskKind::update_velocity),
                      {"particles_update_velocity",
                       {0, n},
                       {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev),
                        Arg::of_float(static_cast<float>(1.0 / substep_dt))},
                       {particle_write(b.v)}});
}

}  // namespace atssim::solver::vertex
