#include "solver/vbd/vbd_plan.hpp"

#include <fmt/format.h>

#include "solver/collision_tasks.hpp"
#include "solver/layout/particle_tables.hpp"
#include "solver/self_contact_tasks.hpp"

namespace atssim::solver::vbd {

plan::SubstepPlan make_vbd_plan(const SimLayout& layout, double substep_dt, int iterations, vertex::VertexBuffers* ids,
                                VbdOrdering ordering) {
  const vertex::VertexLayout vertices = vertex::make_vertex_layout(layout);
  plan::SubstepPlan plan;
  plan.program = std::string(kProgram);
  vertex::VertexBuffers b;
  sched::TaskId last = vertex::begin_vertex_plan(plan, layout, vertices, substep_dt, b);
  const double hi = inertia_dt(layout, substep_dt);  // air drag weighs the inertia (sim_layout.hpp)
  SelfContactBuffers sc = add_self_contact_buffers(plan, layout, b.colliders);
  last = add_self_contact_detection(plan, last, layout, sc, b.x_prev, b.x);
  const float inv_h2 = static_cast<float>(1.0 / (hi * hi));
  // Element k of a color writes particle order[k].
  const auto order =
      std::make_shared<const std::vector<std::int32_t>>(vertices.colors.order.begin(), vertices.colors.order.end());
  // color_batches: element b of a color is batch b, writing its 8 lanes' particles (-1: padding).
  const bool lanes = ordering == VbdOrdering::color_batches;
  const vertex::ColorLanes batches = lanes ? vertex::color_lanes(vertices.colors) : vertex::ColorLanes{};
  const auto lanes_order =
      std::make_shared<const std::vector<std::int32_t>>(batches.order.begin(), batches.order.end());
  const plan::BufferId order_buffer =
      lanes ? plan.add_buffer("vertex_order_lanes", plan::BufferRole::topology, plan::bytes_of(batches.order))
            : b.order;
  // Contact pairs may join two vertices of one colour: the solve reads such a
  // partner from the iteration's start (kernels/contact/self_contact_terms.h),
  // kept by a copy before the first iteration and at the end of every other.
  const bool contact = layout.self_contact.enabled;
  const int n = static_cast<int>(layout.x.size());
  std::vector<std::int32_t> color_of(contact ? n : 0, -1);
  for (int c = 0; contact && c < vertices.colors.count(); ++c) {
    for (int k = vertices.colors.offsets[c]; k < vertices.colors.offsets[c + 1]; ++k) color_of[(*order)[k]] = c;
  }
  const plan::BufferId x_iter =
      plan.add_buffer("sc_x_iter", plan::BufferRole::scratch, std::vector<std::byte>(color_of.size() * kParticleBytes));
  const plan::BufferId color = plan.add_buffer("sc_color", plan::BufferRole::topology, plan::bytes_of(color_of));
  const auto snapshot = [&](int iteration, const std::string& name) {
    if (!contact) return;
    last = plan.add_task_after(last, plan::make_task(name, plan::TaskKind::collision, iteration, 4),
                               {"particles_copy",
                                {0, n},
                                {plan::KernelArg::of_buffer(x_iter), plan::KernelArg::of_buffer(b.x)},
                                {particle_write(x_iter)}});
  };
  snapshot(-1, "contact/iteration_start");
  for (int it = 0; it < iterations; ++it) {
    for (int c = 0; c < vertices.colors.count(); ++c) {
      const std::vector<int>& offsets = lanes ? batches.offsets : vertices.colors.offsets;
      const int first = offsets[c];
      const int count = offsets[c + 1] - first;
      using Arg = plan::KernelArg;
      std::vector<Arg> args{Arg::of_buffer(b.x),
                            Arg::of_buffer(b.x_tilde),
                            Arg::of_buffer(b.adjacency_offsets),
                            Arg::of_buffer(b.adjacency),
                            Arg::of_buffer(b.stretch),
                            Arg::of_buffer(b.bend),
                            Arg::of_buffer(b.tets),
                            Arg::of_buffer(order_buffer),
                            Arg::of_float(inv_h2),
                            Arg::of_int(layout.has_ground ? 1 : 0),
                            Arg::of_float(layout.ground_y)};
      for (const Arg& a : vertex::collider_args(layout, b)) args.push_back(a);
      for (const Arg& a : vertex::damping_args(layout, b, substep_dt)) args.push_back(a);
      for (const Arg& a : self_contact_args(layout, sc, hi)) args.push_back(a);
      args.push_back(Arg::of_buffer(x_iter));
      args.push_back(Arg::of_buffer(color));
      last =
          plan.add_task_after(last, plan::make_task(fmt::format("it{}/vertex/c{}", it + 1, c), kVertex, it, c),
                              {lanes ? "vbd_solve_lanes" : "vbd_solve",
                               {first, count},
                               std::move(args),
                               {lanes ? plan::WriteSpan::per_index(b.x, kParticleBytes, vertex::kLaneWidth, lanes_order)
                                      : plan::WriteSpan::per_index(b.x, kParticleBytes, 1, order)}});
    }
    last = add_ground_task(plan, last, layout, b.x, it);
    if (it + 1 < iterations) snapshot(it, fmt::format("it{}/collision/iteration_end", it + 1));
  }
  last = add_self_contact_friction(plan, last, layout, sc, b.x_prev, b.x, b.v, b.friction, substep_dt);
  vertex::end_vertex_plan(plan, layout, last, b, substep_dt);
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::vbd
