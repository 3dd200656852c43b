#include "solver/sosd/sosd_plan.hpp"

#include <array>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "solver/collision_tasks.hpp"
#include "solver/layout/particle_tables.hpp"
#include "solver/self_contact_tasks.hpp"

namespace atssim::solver::sosd {

namespace {

void append_blocks(std::vector<StencilBlock>& out, int kind, const std::vector<int>& offsets) {
  for (std::size_t c = 0; c + 1 < offsets.size(); ++c) {
    if (offsets[c + 1] > offsets[c]) out.push_back({kind, offsets[c], offsets[c + 1]});
  }
}

}  // namespace

std::vector<StencilBlock> stencil_blocks(const SimLayout& layout) {
  std::vector<StencilBlock> blocks;
  append_blocks(blocks, 0, layout.stretch_blocks);
  append_blocks(blocks, 1, layout.bend_blocks);
  append_blocks(blocks, 2, layout.tet_blocks);
  return blocks;
}

plan::SubstepPlan make_sosd_plan(const SimLayout& layout, double substep_dt, int iterations, double step,
                                 vertex::VertexBuffers* ids, SosdOrdering ordering) {
  const vertex::VertexLayout vertices = vertex::make_vertex_layout(layout);
  plan::SubstepPlan plan;
  plan.program = std::string(kProgram);
  vertex::VertexBuffers b;
  sched::TaskId last = vertex::begin_vertex_plan(plan, layout, vertices, substep_dt, b);
  const int n = plan.particle_count;
  constexpr std::size_t kFloat4 = 4 * sizeof(float);
  using plan::BufferRole;
  const plan::BufferId systems =
      plan.add_buffer("vertex_systems", BufferRole::scratch, std::vector<std::byte>(4 * n * kFloat4));
  const std::array<plan::BufferId, 3> d{
      plan.add_buffer("d_stretch", BufferRole::scratch, std::vector<std::byte>(2 * layout.stretch.size() * kFloat4)),
      plan.add_buffer("d_bend", BufferRole::scratch, std::vector<std::byte>(4 * layout.bend.size() * kFloat4)),
      plan.add_buffer("d_tet", BufferRole::scratch, std::vector<std::byte>(4 * layout.tets.size() * kFloat4))};
  const std::array<plan::BufferId, 3> elements{b.stretch, b.bend, b.tets};
  constexpr std::array<const char*, 3> kKinds{"stretch", "bend", "tet"};
  const std::vector<StencilBlock> blocks = stencil_blocks(layout);
  const std::array<int, 3> kind_count{static_cast<int>(layout.stretch.size()), static_cast<int>(layout.bend.size()),
                                      static_cast<int>(layout.tets.size())};
  std::array<int, 3> first_block{0, 0, 0};  // index in `blocks` of each kind's first color
  for (int i = static_cast<int>(blocks.size()) - 1; i >= 0; --i) first_block[blocks[i].kind] = i;
  const double hi = inertia_dt(layout, substep_dt);  // air drag weighs the inertia (sim_layout.hpp)
  const float inv_h2 = static_cast<float>(1.0 / (hi * hi));
  using Arg = plan::KernelArg;
  const std::vector<Arg> damping = vertex::damping_args(layout, b, substep_dt);
  SelfContactBuffers sc = add_self_contact_buffers(plan, layout, b.colliders);
  last = add_self_contact_detection(plan, last, layout, sc, b.x_prev, b.x);
  const std::vector<Arg> sc_args = self_contact_args(layout, sc, hi);
  // color_batches: each color block of bending stencils padded with -1 to
  // whole batches of 8; batch_at[k] is the batch where the block starting
  // at stencil k starts (every range launched below starts and ends on a
  // block's bounds).
  const bool lanes = ordering == SosdOrdering::color_batches && kind_count[1] > 0 && layout.bend_blocks.size() >= 2 &&
                     layout.bend_blocks.front() == 0 && layout.bend_blocks.back() == kind_count[1];
  std::vector<std::int32_t> bend_order;
  std::map<int, int> batch_at;
  for (std::size_t c = 0; lanes && c + 1 < layout.bend_blocks.size(); ++c) {
    batch_at[layout.bend_blocks[c]] = static_cast<int>(bend_order.size()) / vertex::kLaneWidth;
    for (int k = layout.bend_blocks[c]; k < layout.bend_blocks[c + 1]; ++k) bend_order.push_back(k);
    bend_order.resize((bend_order.size() + vertex::kLaneWidth - 1) / vertex::kLaneWidth * vertex::kLaneWidth, -1);
  }
  batch_at[kind_count[1]] = static_cast<int>(bend_order.size()) / vertex::kLaneWidth;
  const auto lanes_order = std::make_shared<const std::vector<std::int32_t>>(std::move(bend_order));
  const plan::BufferId order =
      lanes ? plan.add_buffer("bend_order_lanes", BufferRole::topology, plan::bytes_of(*lanes_order)) : -1;
  for (int it = 0; it < iterations; ++it) {
    std::vector<Arg> system_args{
        Arg::of_buffer(b.x),         Arg::of_buffer(b.x_tilde), Arg::of_buffer(b.adjacency_offsets),
        Arg::of_buffer(b.adjacency), Arg::of_buffer(b.stretch), Arg::of_buffer(b.bend),
        Arg::of_buffer(b.tets),      Arg::of_buffer(systems),   Arg::of_float(inv_h2)};
    for (const Arg& a : vertex::collider_args(layout, b)) system_args.push_back(a);
    system_args.insert(system_args.end(), damping.begin(), damping.end());
    system_args.insert(system_args.end(), sc_args.begin(), sc_args.end());
    const sched::TaskId systems_task = plan.add_task_after(
        last, plan::make_task(fmt::format("it{}/systems", it + 1), kSystems, it),
        {"sosd_vertex_systems", {0, n}, std::move(system_args), {plan::WriteSpan::per_element(systems, 4 * kFloat4)}});
    // All stencils read the same x^k and vertex systems, so a block matters
    // only as the main one: one task for it, and per kind one task for the
    // rest (the Jacobi blocks: up to two element ranges around the main).
    const StencilBlock main = blocks.empty() ? StencilBlock{-1, 0, 0} : blocks[it % blocks.size()];
    std::vector<sched::TaskId> stencil_tasks;
    const auto launch = [&](int kind, int first, int end) {
      if (lanes && kind == 1) {
        const int batch = batch_at.at(first);
        return plan::KernelLaunch{"sosd_bend_lanes",
                                  {batch, batch_at.at(end) - batch},
                                  {Arg::of_buffer(b.x), Arg::of_buffer(systems), Arg::of_buffer(b.bend),
                                   Arg::of_buffer(order), Arg::of_buffer(d[1])},
                                  {plan::WriteSpan::per_index(d[1], 4 * kFloat4, vertex::kLaneWidth, lanes_order)}};
      }
      std::vector<Arg> args{Arg::of_buffer(b.x), Arg::of_buffer(systems), Arg::of_buffer(elements[kind]),
                            Arg::of_buffer(d[kind])};
      if (kind == 0) args.insert(args.end(), damping.begin(), damping.end());
      return plan::KernelLaunch{fmt::format("sosd_{}", kKinds[kind]),
                                {first, end - first},
                                std::move(args),
                                {plan::WriteSpan::per_element(d[kind], (kind == 0 ? 2 : 4) * kFloat4)}};
    };
    if (main.kind >= 0) {
      const int color = static_cast<int>(it % blocks.size()) - first_block[main.kind];
      stencil_tasks.push_back(plan.add_task(
          plan::make_task(fmt::format("it{}/main/{}/c{}", it + 1, kKinds[main.kind], color), kMainBlock, it, color),
          {launch(main.kind, main.first, main.end)}));
    }
    for (int kind = 0; kind < 3; ++kind) {
      if (kind_count[kind] == 0) continue;
      std::vector<plan::KernelLaunch> rest;
      if (kind != main.kind) {
        rest.push_back(launch(kind, 0, kind_count[kind]));
      } else {
        if (main.first > 0) rest.push_back(launch(kind, 0, main.first));
        if (main.end < kind_count[kind]) rest.push_back(launch(kind, main.end, kind_count[kind]));
      }
      if (rest.empty()) continue;
      stencil_tasks.push_back(
          plan.add_task(plan::make_task(fmt::format("it{}/{}", it + 1, kKinds[kind]), kStencils, it), std::move(rest)));
    }
    for (sched::TaskId t : stencil_tasks) plan.graph.add_edge(systems_task, t);
    const sched::TaskId combine = plan.add_task(
        plan::make_task(fmt::format("it{}/combine", it + 1), kCombine, it),
        {{"sosd_combine",
          {0, n},
          with_colliders({Arg::of_buffer(b.x), Arg::of_buffer(b.adjacency_offsets), Arg::of_buffer(b.adjacency),
                          Arg::of_buffer(d[0]), Arg::of_buffer(d[1]), Arg::of_buffer(d[2]), Arg::of_buffer(systems),
                          Arg::of_int(main.kind), Arg::of_int(main.first), Arg::of_int(main.end),
                          Arg::of_float(static_cast<float>(step)), Arg::of_int(layout.has_ground ? 1 : 0),
                          Arg::of_float(layout.ground_y)},
                         layout, b.colliders, {Arg::of_int(layout.self_contact.enabled ? 1 : 0)}),
          {particle_write(b.x)}}});
    for (sched::TaskId t : stencil_tasks) plan.graph.add_edge(t, combine);
    if (stencil_tasks.empty()) plan.graph.add_edge(systems_task, combine);
    last = add_ground_task(plan, add_self_contact_clamp(plan, combine, layout, sc, b.x_prev, b.x, it), layout, b.x, it);
  }
  last = add_self_contact_friction(plan, last, layout, sc, b.x_prev, b.x, b.v, b.friction, substep_dt);
  vertex::end_vertex_plan(plan, layout, last, b, substep_dt);
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::sosd
