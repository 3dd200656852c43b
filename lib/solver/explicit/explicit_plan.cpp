#include "solver/explicit/explicit_plan.hpp"

#include <fmt/format.h>

#include "solver/collision_tasks.hpp"
#include "solver/layout/particle_tables.hpp"

namespace atssim::solver::explicit_rk {

namespace {

using Arg = plan::KernelArg;

// One explicit Runge-Kutta stage: its slopes' weight in the final sum, and
// the fraction of h at which the next stage is taken.
struct Stage {
  float weight;
  float next;
};

}  // namespace

int evaluations(Integrator integrator) {
  switch (integrator) {
    case Integrator::semi_euler:
      return 1;
    case Integrator::midpoint:
      return 2;
    case Integrator::rk4:
      break;
  }
  return 4;
}

plan::SubstepPlan make_explicit_plan(const SimLayout& layout, const ExplicitSettings& settings, ExplicitBuffers* ids) {
  const vertex::VertexLayout vertices = vertex::make_vertex_layout(layout);
  plan::SubstepPlan plan;
  plan.program = std::string(kProgram);
  const int n = static_cast<int>(layout.x.size());
  plan.particle_count = n;
  using plan::BufferRole;
  ExplicitBuffers b;
  b.x = plan.add_buffer("x", BufferRole::positions, plan::bytes_of(layout.x));
  b.v = plan.add_buffer("v", BufferRole::velocities, plan::bytes_of(layout.v));
  b.xs = plan.add_buffer("x_stage", BufferRole::scratch, plan::bytes_of(layout.x));
  b.vs = plan.add_buffer("v_stage", BufferRole::scratch, plan::bytes_of(layout.v));
  b.a = plan.add_buffer("acceleration", BufferRole::scratch, plan::bytes_of(layout.v));
  b.sum_x = plan.add_buffer("sum_x", BufferRole::scratch, plan::bytes_of(layout.v));
  b.sum_v = plan.add_buffer("sum_v", BufferRole::scratch, plan::bytes_of(layout.v));
  b.stretch = plan.add_buffer("stretch", BufferRole::elements, plan::bytes_of(layout.stretch));
  b.bend = plan.add_buffer("bend", BufferRole::elements, plan::bytes_of(layout.bend));
  b.tets = plan.add_buffer("tets", BufferRole::elements, plan::bytes_of(layout.tets));
  b.adjacency_offsets =
      plan.add_buffer("adjacency_offsets", BufferRole::topology, plan::bytes_of(vertices.adjacency_offsets));
  b.adjacency = plan.add_buffer("adjacency", BufferRole::topology, plan::bytes_of(vertices.adjacency));

  const float h = static_cast<float>(settings.substep_dt);
  const auto forces = [&](sched::TaskId after, int stage, plan::BufferId xs, plan::BufferId vs) {
    plan::KernelLaunch launch{
        "explicit_forces",
        {0, n},
        {Arg::of_buffer(xs), Arg::of_buffer(vs), Arg::of_buffer(b.a), Arg::of_buffer(b.adjacency_offsets),
         Arg::of_buffer(b.adjacency), Arg::of_buffer(b.stretch), Arg::of_buffer(b.bend), Arg::of_buffer(b.tets),
         Arg::of_float(layout.gravity.x), Arg::of_float(layout.gravity.y), Arg::of_float(layout.gravity.z),
         Arg::of_float(layout.air_drag)},
        {particle_write(b.a)}};
    const sched::Task task = plan::make_task(fmt::format("forces/s{}", stage + 1), plan::TaskKind::jacobi, -1, stage);
    return stage == 0 ? plan.add_task(task, {launch}) : plan.add_task_after(after, task, launch);
  };
  sched::TaskId last = 0;  // the first forces task has no predecessor
  if (settings.integrator == Integrator::semi_euler) {
    last = forces(last, 0, b.x, b.v);
    last = plan.add_task_after(last, plan::make_task("integrate/semi_euler", plan::TaskKind::jacobi, -1, 0),
                               {"explicit_semi_euler",
                                {0, n},
                                {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.a), Arg::of_float(h)},
                                {particle_write(b.x), particle_write(b.v)}});
  } else {
    // Butcher tableaux of seed 001 Eqs. 3 (midpoint) and 4 (classic RK4):
    // stage k's slopes weigh `weight`, the next stage sits at `next` h.
    const std::vector<Stage> stages = settings.integrator == Integrator::midpoint
                                          ? std::vector<Stage>{{0.0f, 0.5f}, {1.0f, 0.0f}}
                                          : std::vector<Stage>{{1.0f, 0.5f}, {2.0f, 0.5f}, {2.0f, 1.0f}, {1.0f, 0.0f}};
    const float total = settings.integrator == Integrator::midpoint ? 1.0f : 6.0f;
    for (std::size_t s = 0; s < stages.size(); ++s) {
      const int stage = static_cast<int>(s);
      last = forces(last, stage, s == 0 ? b.x : b.xs, s == 0 ? b.v : b.vs);
      if (s + 1 < stages.size()) {
        last = plan.add_task_after(
            last, plan::make_task(fmt::format("integrate/s{}", stage + 1), plan::TaskKind::jacobi, -1, stage),
            {"explicit_stage",
             {0, n},
             {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.xs), Arg::of_buffer(b.vs), Arg::of_buffer(b.a),
              Arg::of_buffer(b.sum_x), Arg::of_buffer(b.sum_v), Arg::of_float(stages[s].weight),
              Arg::of_float(stages[s].next * h), Arg::of_int(s == 0 ? 1 : 0)},
             {particle_write(b.xs), particle_write(b.vs), particle_write(b.sum_x), particle_write(b.sum_v)}});
      } else {
        last = plan.add_task_after(last, plan::make_task("integrate/finish", plan::TaskKind::jacobi, -1, stage),
                                   {"explicit_finish",
                                    {0, n},
                                    {Arg::of_buffer(b.x), Arg::of_buffer(b.v), Arg::of_buffer(b.vs),
                                     Arg::of_buffer(b.a), Arg::of_buffer(b.sum_x), Arg::of_buffer(b.sum_v),
                                     Arg::of_float(stages[s].weight), Arg::of_float(h / total)},
                                    {particle_write(b.x), particle_write(b.v)}});
      }
    }
  }
  add_ground_task(plan, last, layout, b.x, 0);
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::explicit_rk
