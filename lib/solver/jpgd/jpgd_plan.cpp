#include "solver/jpgd/jpgd_plan.hpp"

#include <fmt/format.h>

#include "solver/collision_tasks.hpp"
#include "solver/layout/particle_tables.hpp"
#include "solver/self_contact_tasks.hpp"

namespace atssim::solver::jpgd {

std::vector<double> chebyshev_weights(int iterations, double rho) {
  std::vector<double> omega;
  for (int k = 0; k < iterations; ++k) {
    if (k == 0) {
      omega.push_back(1.0);
    } else if (k == 1) {
      omega.push_back(2.0 / (2.0 - rho * rho));
    } else {
      omega.push_back(4.0 / (4.0 - rho * rho * omega.back()));
    }
  }
  return omega;
}

plan::SubstepPlan make_jpgd_plan(const SimLayout& layout, const JpgdSettings& settings, vertex::VertexBuffers* ids) {
  const vertex::VertexLayout vertices = vertex::make_vertex_layout(layout);
  plan::SubstepPlan plan;
  plan.program = std::string(kProgram);
  vertex::VertexBuffers b;
  sched::TaskId last = vertex::begin_vertex_plan(plan, layout, vertices, settings.substep_dt, b);
  const int n = plan.particle_count;
  // x^{k+1} goes to a different buffer than x^k and x^{k-1}: three rotate.
  const plan::BufferId rotation[3] = {b.x, plan.add_buffer("x_1", plan::BufferRole::scratch, plan::bytes_of(layout.x)),
                                      plan.add_buffer("x_2", plan::BufferRole::scratch, plan::bytes_of(layout.x))};
  const double hi = inertia_dt(layout, settings.substep_dt);  // air drag weighs the inertia (sim_layout.hpp)
  const float inv_h2 = static_cast<float>(1.0 / (hi * hi));
  const bool heavy_ball = settings.momentum > 0.0;
  SelfContactBuffers sc = add_self_contact_buffers(plan, layout, b.colliders);
  last = add_self_contact_detection(plan, last, layout, sc, b.x_prev, b.x);
  const std::vector<double> omega = chebyshev_weights(settings.iterations, heavy_ball ? 0.0 : settings.chebyshev_rho);
  const float beta = heavy_ball ? static_cast<float>(settings.momentum) : 0.0f;
  // vertex_batches: element b is batch b, writing its 8 lanes' particles (-1: padding).
  const bool lanes = settings.ordering == vertex::JacobiOrdering::vertex_batches;
  const auto lanes_order =
      std::make_shared<const std::vector<std::int32_t>>(lanes ? vertex::vertex_lanes(n) : std::vector<int>{});
  const plan::BufferId order =
      lanes ? plan.add_buffer("vertex_order_lanes", plan::BufferRole::topology, plan::bytes_of(*lanes_order)) : -1;
  using Arg = plan::KernelArg;
  for (int it = 0; it < settings.iterations; ++it) {
    const plan::BufferId current = rotation[it % 3];
    const plan::BufferId before = it == 0 ? current : rotation[(it + 2) % 3];
    const plan::BufferId next = rotation[(it + 1) % 3];
    std::vector<Arg> args{Arg::of_buffer(current),
                          Arg::of_buffer(before),
                          Arg::of_buffer(next),
                          Arg::of_buffer(b.x_tilde),
                          Arg::of_buffer(b.adjacency_offsets),
                          Arg::of_buffer(b.adjacency),
                          Arg::of_buffer(b.stretch),
                          Arg::of_buffer(b.bend),
                          Arg::of_buffer(b.tets)};
    if (lanes) args.push_back(Arg::of_buffer(order));
    for (const Arg& a : {Arg::of_float(inv_h2), Arg::of_float(static_cast<float>(settings.step)),
                         Arg::of_float(static_cast<float>(omega[it])), Arg::of_float(it == 0 ? 0.0f : beta),
                         Arg::of_int(layout.has_ground ? 1 : 0), Arg::of_float(layout.ground_y)})
      args.push_back(a);
    for (const Arg& a : vertex::collider_args(layout, b)) args.push_back(a);
    for (const Arg& a : vertex::damping_args(layout, b, settings.substep_dt)) args.push_back(a);
    for (const Arg& a : self_contact_args(layout, sc, hi)) args.push_back(a);
    const sched::TaskId t =
        plan.add_task_after(last, plan::make_task(fmt::format("it{}/jacobi", it + 1), plan::TaskKind::jacobi, it, 0),
                            {lanes ? "jpgd_step_lanes" : "jpgd_step",
                             {0, lanes ? static_cast<int>(lanes_order->size()) / vertex::kLaneWidth : n},
                             std::move(args),
                             {lanes ? plan::WriteSpan::per_index(next, kParticleBytes, vertex::kLaneWidth, lanes_order)
                                    : particle_write(next)}});
    last = add_ground_task(plan, add_self_contact_clamp(plan, t, layout, sc, b.x_prev, next, it), layout, next, it);
    if (!layout.self_contact.enabled) last = add_contact_task(plan, last, layout, b.colliders, next, it);
  }
  const plan::BufferId result = rotation[settings.iterations % 3];
  if (result != b.x) {
    last = plan.add_task_after(
        last, plan::make_task("copy_result", plan::TaskKind::copy),
        {"particles_copy", {0, n}, {Arg::of_buffer(b.x), Arg::of_buffer(result)}, {particle_write(b.x)}});
  }
  last = add_self_contact_friction(plan, last, layout, sc, b.x_prev, b.x, b.v, b.friction, settings.substep_dt);
  vertex::end_vertex_plan(plan, layout, last, b, settings.substep_dt);
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::jpgd
