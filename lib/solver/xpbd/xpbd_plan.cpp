#include "solver/xpbd/xpbd_plan.hpp"

#include <cstring>

#include <fmt/format.h>

#include "common/xpbd_tet.h"
#include "solver/collision_tasks.hpp"
#include "solver/layout/particle_tables.hpp"
#include "solver/self_contact_tasks.hpp"
#include "solver/xpbd/xpbd_batches.hpp"

#include "util/error.hpp"

namespace atssim::solver::xpbd {

namespace {

using Arg = plan::KernelArg;

// Adds one task per color block of one element set, chained after `last`.
// Each writes its elements' particles and its multipliers (`lambda_bytes`
// per element).
sched::TaskId add_blocks(plan::SubstepPlan& plan, sched::TaskId last, const std::vector<int>& blocks,
                         const plan::TaskKind& kind, const std::string& function, plan::BufferId x,
                         plan::BufferId elements, plan::BufferId lambda, float dt, int iteration,
                         const std::shared_ptr<const std::vector<std::int32_t>>& particles, int arity,
                         std::uint32_t lambda_bytes, const std::vector<Arg>& extra = {}) {
  for (int b = 0; b + 1 < static_cast<int>(blocks.size()); ++b) {
    const std::string name = fmt::format("it{}/{}/c{}", iteration + 1, plan::to_string(kind), b);
    std::vector<Arg> args{Arg::of_buffer(x), Arg::of_buffer(elements), Arg::of_buffer(lambda), Arg::of_float(dt),
                          Arg::of_int(iteration == 0 ? 1 : 0)};
    args.insert(args.end(), extra.begin(), extra.end());
    last = plan.add_task_after(last, plan::make_task(name, kind, iteration, b),
                               {function,
                                {blocks[b], blocks[b + 1] - blocks[b]},
                                std::move(args),
                                {plan::WriteSpan::per_index(x, kParticleBytes, arity, particles),
                                 plan::WriteSpan::per_element(lambda, lambda_bytes)}});
  }
  return last;
}

// solver.ordering: batches. One task sweeps the whole padded set batch after
// batch in one work-item (range {0, 1}); `extra` as for add_blocks, then the
// batch count and the particle count (a lane at or past it is the dummy).
sched::TaskId add_batch_sweep(plan::SubstepPlan& plan, sched::TaskId last, int batches, const plan::TaskKind& kind,
                              const std::string& function, plan::BufferId x, plan::BufferId elements,
                              plan::BufferId lambda, float dt, int iteration, const std::vector<Arg>& extra = {}) {
  const std::string name = fmt::format("it{}/{}/batches", iteration + 1, plan::to_string(kind));
  std::vector<Arg> args{Arg::of_buffer(x), Arg::of_buffer(elements), Arg::of_buffer(lambda), Arg::of_float(dt),
                        Arg::of_int(iteration == 0 ? 1 : 0)};
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back(Arg::of_int(batches));
  args.push_back(Arg::of_int(plan.particle_count));
  return plan.add_task_after(
      last, plan::make_task(name, kind, iteration, 0),
      {function, {0, 1}, std::move(args), {plan::WriteSpan::whole_buffer(x), plan::WriteSpan::whole_buffer(lambda)}});
}

// The strain constraints (common/xpbd_tet.h) minimise the StVK energy; solving
// them for a neo-Hookean solid would silently change its material.
void check_tets_are_stvk(const SimLayout& layout) {
  for (const ats_tet_c& t : layout.tets) {
    if (t.model != ATS_TET_STVK) {
      throw input_error(
          "solver.method xpbd simulates solids with material model: stvk only (its strain "
          "constraints are the StVK energy); set the solid's material.model to stvk, or use "
          "another solver.method for neo_hookean (atssim methods lists the models each simulates)");
    }
  }
}

}  // namespace

plan::SubstepPlan make_xpbd_plan(const SimLayout& layout, const XpbdSettings& settings, XpbdBuffers* ids) {
  plan::SubstepPlan plan;
  plan.program = std::string(kProgram);
  plan.particle_count = static_cast<int>(layout.x.size());
  XpbdBuffers b;
  using plan::BufferRole;
  const bool batched = settings.ordering == XpbdOrdering::batches;
  if (batched)
    plan.one_device_reason =
        "solver.ordering 'batches' sweeps each element set in one task on one device (color_batches cuts "
        "each color block into batches of 8 lanes and runs on two)";
  const int n = plan.particle_count;
  const auto stretch_batches = batched ? batch_elements(layout.stretch, n) : ElementBatches<ats_distance_c>{};
  const auto bend_batches = batched ? batch_elements(layout.bend, n) : ElementBatches<ats_bend_c>{};
  // solver.ordering: color_batches: the color blocks cut into batches of 8 lanes.
  const bool lanes = settings.ordering == XpbdOrdering::color_batches;
  const auto stretch_lanes =
      lanes ? color_batches(layout.stretch, layout.stretch_blocks, n) : ColorBatches<ats_distance_c>{};
  const auto bend_lanes = lanes ? color_batches(layout.bend, layout.bend_blocks, n) : ColorBatches<ats_bend_c>{};
  const auto tet_batches = batched ? batch_elements(layout.tets, n) : ElementBatches<ats_tet_c>{};
  const auto tet_lanes = lanes ? color_batches(layout.tets, layout.tet_blocks, n) : ColorBatches<ats_tet_c>{};
  b.x = plan.add_buffer("x", BufferRole::positions, plan::bytes_of(layout.x));
  b.v = plan.add_buffer("v", BufferRole::velocities, plan::bytes_of(layout.v));
  b.x_prev = plan.add_buffer("x_prev", BufferRole::start_positions, plan::bytes_of(layout.x));
  if (!layout.stretch.empty()) {
    const auto& stretch = batched ? stretch_batches.elements : lanes ? stretch_lanes.set.elements : layout.stretch;
    b.stretch = plan.add_buffer("stretch", BufferRole::elements, plan::bytes_of(stretch));
    b.stretch_lambda = plan.add_buffer("stretch_lambda", BufferRole::multipliers,
                                       std::vector<std::byte>(stretch.size() * sizeof(float)));
  }
  if (!layout.bend.empty()) {
    const auto& bend = batched ? bend_batches.elements : lanes ? bend_lanes.set.elements : layout.bend;
    b.bend = plan.add_buffer("bend", BufferRole::elements, plan::bytes_of(bend));
    b.bend_lambda = plan.add_buffer("bend_lambda", BufferRole::multipliers,
                                    std::vector<std::byte>(bend.size() * 4 * sizeof(float)));
  }
  if (!layout.tets.empty()) {
    check_tets_are_stvk(layout);
    const auto& tets = batched ? tet_batches.elements : lanes ? tet_lanes.set.elements : layout.tets;
    b.tet = plan.add_buffer("tet", BufferRole::elements, plan::bytes_of(tets));
    b.tet_lambda = plan.add_buffer("tet_lambda", BufferRole::multipliers,
                                   std::vector<std::byte>(tets.size() * ATS_TET_LAMBDA_STRIDE * sizeof(float)));
  }

  // The step of predict and the velocity update; the constraints weigh the
  // inertia as for inertia_dt (air drag, solver/layout/sim_layout.hpp).
  const float h = static_cast<float>(settings.substep_dt);
  const float dt = static_cast<float>(inertia_dt(layout, settings.substep_dt));
  const ColliderBuffers colliders = layout.colliders.empty() ? ColliderBuffers{} : add_collider_buffers(plan, layout);
  sched::TaskId last =
      plan.add_task(plan::make_task("predict", plan::TaskKind::predict),
                    {{"xpbd_predict",
                      {0, n},
                      {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev), Arg::of_float(h),
                       Arg::of_float(layout.gravity.x), Arg::of_float(layout.gravity.y),
                       Arg::of_float(layout.gravity.z), Arg::of_float(velocity_damping(layout, settings.substep_dt))},
                      {particle_write(b.x), particle_write(b.v), particle_write(b.x_prev)}}});
  last = add_collider_near_task(plan, last, layout, colliders, b.x);
  // Material damping along the springs (common/xpbd_distance.h): the start positions and 1/h, 0 = none.
  const std::vector<Arg> spring_damping{Arg::of_buffer(b.x_prev),
                                        Arg::of_float(has_spring_damping(layout) ? 1.0f / h : 0.0f)};
  SelfContactBuffers sc = add_self_contact_buffers(plan, layout, colliders);
  add_self_contact_projection_buffers(plan, layout, sc);
  last = add_self_contact_detection(plan, last, layout, sc, b.x_prev, b.x);
  const auto stretch_particles = particles_of(lanes ? stretch_lanes.set.elements : layout.stretch);
  const auto bend_particles = particles_of(lanes ? bend_lanes.set.elements : layout.bend);
  // A batch of lanes writes its kBatchWidth elements' particles and multipliers.
  const int width = lanes ? kBatchWidth : 1;
  std::vector<Arg> stretch_extra = spring_damping, lanes_extra;
  if (lanes) {
    stretch_extra.push_back(Arg::of_int(n));
    lanes_extra.push_back(Arg::of_int(n));
  }
  const auto tet_particles = particles_of(lanes ? tet_lanes.set.elements : layout.tets);
  for (int it = 0; it < settings.iterations; ++it) {
    if (b.stretch >= 0 && batched) {
      last = add_batch_sweep(plan, last, stretch_batches.batches(), kStretch, "xpbd_stretch_batches", b.x, b.stretch,
                             b.stretch_lambda, dt, it, spring_damping);
    } else if (b.stretch >= 0) {
      last = add_blocks(plan, last, lanes ? stretch_lanes.blocks : layout.stretch_blocks, kStretch,
                        lanes ? "xpbd_stretch_lanes" : "xpbd_stretch", b.x, b.stretch, b.stretch_lambda, dt, it,
                        stretch_particles, 2 * width, width * sizeof(float), stretch_extra);
    }
    if (b.bend >= 0 && batched) {
      last = add_batch_sweep(plan, last, bend_batches.batches(), kBend, "xpbd_bend_batches", b.x, b.bend, b.bend_lambda,
                             dt, it);
    } else if (b.bend >= 0) {
      last = add_blocks(plan, last, lanes ? bend_lanes.blocks : layout.bend_blocks, kBend,
                        lanes ? "xpbd_bend_lanes" : "xpbd_bend", b.x, b.bend, b.bend_lambda, dt, it, bend_particles,
                        4 * width, width * 4 * sizeof(float), lanes_extra);
    }
    if (b.tet >= 0 && batched) {
      last = add_batch_sweep(plan, last, tet_batches.batches(), kTet, "xpbd_tet_batches", b.x, b.tet, b.tet_lambda, dt,
                             it);
    } else if (b.tet >= 0) {
      last = add_blocks(plan, last, lanes ? tet_lanes.blocks : layout.tet_blocks, kTet,
                        lanes ? "xpbd_tet_lanes" : "xpbd_tet", b.x, b.tet, b.tet_lambda, dt, it, tet_particles,
                        4 * width, width * ATS_TET_LAMBDA_STRIDE * sizeof(float), lanes_extra);
    }
    last = add_self_contact_projection(plan, last, layout, sc, b.x_prev, b.x, it);
    last = add_ground_task(plan, last, layout, b.x, it);
    last = add_contact_task(plan, last, layout, colliders, b.x, it);
  }
  const plan::BufferId friction = add_friction_buffer(plan, layout);
  last = add_self_contact_friction(plan, last, layout, sc, b.x_prev, b.x, b.v, friction, settings.substep_dt);
  last = add_friction_task(plan, last, layout, colliders, friction, b.x, b.x_prev, b.v, settings.substep_dt);
  plan.add_task_after(last, plan::make_task("update_velocity", plan::TaskKind::update_velocity),
                      {"particles_update_velocity",
                       {0, n},
                       {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.x_prev), Arg::of_float(1.0f / h)},
                       {particle_write(b.v)}});
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::xpbd
