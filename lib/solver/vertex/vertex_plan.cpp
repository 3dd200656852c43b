#include "solver/vertex/vertex_plan.hpp"

#include "solver/energy/finite_stiffness.hpp"

namespace atssim::solver::vertex {

using Arg = KernelArg;

sched::TaskId begin_vertex_plan(SubstepPlan& plan, const SimLayout& layout, const VertexLayout& vertices,
                                double substep_dt, VertexBuffers& b) {
  energy::require_finite_stiffness(layout);
  const int n = static_cast<int>(layout.x.size());
  plan.particle_count = n;
  b.x = plan.add_buffer("x", bytes_of(layout.x));
  b.v = plan.add_buffer("v", bytes_of(layout.v));
  b.x_prev = plan.add_buffer("x_prev", bytes_of(layout.x));
  b.x_tilde = plan.add_buffer("x_tilde", bytes_of(layout.x));
  b.stretch = plan.add_buffer("stretch", bytes_of(layout.stretch));
  b.bend = plan.add_buffer("bend", bytes_of(layout.bend));
  b.tets = plan.add_buffer("tets", bytes_of(layout.tets));
  b.adjacency_offsets = plan.add_buffer("adjacency_offsets", bytes_of(vertices.adjacency_offsets));
  b.adjacency = plan.add_buffer("adjacency", bytes_of(vertices.adjacency));
  b.order = plan.add_buffer("vertex_order", bytes_of(vertices.colors.order));
  plan.positions = b.x;
  const float dt = static_cast<float>(substep_dt);
  return plan.add_task({"predict", "predict", -1, -1},
                       {{"particles_predict", static_cast<std::size_t>(n),
                         {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev), Arg::of_buffer(b.x_tilde),
                          Arg::of_float(dt), Arg::of_float(layout.gravity.x), Arg::of_float(layout.gravity.y),
                          Arg::of_float(layout.gravity.z), Arg::of_int(0), Arg::of_int(n)},
                         8}});
}

void end_vertex_plan(SubstepPlan& plan, sched::TaskId last, const VertexBuffers& b, double substep_dt) {
  const int n = plan.particle_count;
  const sched::TaskId update = plan.add_task(
      {"update_velocity", "update_velocity", -1, -1},
      {{"particles_update_velocity", static_cast<std::size_t>(n),
        {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev),
         Arg::of_float(static_cast<float>(1.0 / substep_dt)), Arg::of_int(0), Arg::of_int(n)},
        4}});
  plan.graph.add_edge(last, update);
}

}  // namespace atssim::solver::vertex
