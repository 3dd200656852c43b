#include "solver/energy/energy_plan.hpp"

#include <cstring>

#include <fmt/format.h>

#include "solver/energy/finite_stiffness.hpp"
#include "util/error.hpp"

namespace atssim::solver::energy {

namespace {

using Arg = plan::KernelArg;

plan::KernelLaunch element_launch(const char* function, plan::BufferId x, plan::BufferId elements, plan::BufferId out,
                                  int out_first, int count) {
  return {function,
          {0, count},
          {Arg::of_buffer(x), Arg::of_buffer(elements), Arg::of_buffer(out), Arg::of_int(out_first)},
          {plan::WriteSpan::per_element(out, sizeof(float), out_first)}};
}

}  // namespace

EnergyOutput energy_output(const SimLayout& layout) {
  EnergyOutput o;
  o.inertia_first = 0;
  o.stretch_first = static_cast<int>(layout.x.size());
  o.bend_first = o.stretch_first + static_cast<int>(layout.stretch.size());
  o.tet_first = o.bend_first + static_cast<int>(layout.bend.size());
  o.size = o.tet_first + static_cast<int>(layout.tets.size());
  return o;
}

plan::SubstepPlan make_energy_plan(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                                   EnergyBuffers* ids) {
  if (predicted.size() != layout.x.size()) {
    throw internal_error(
        fmt::format("energy plan: {} predicted positions for {} particles", predicted.size(), layout.x.size()));
  }
  require_finite_stiffness(layout);  // the device would compute inf or NaN
  require_valid_tets(layout);
  const EnergyOutput where = energy_output(layout);

  plan::SubstepPlan plan;
  plan.program = "xpbd_energy";
  plan.particle_count = static_cast<int>(layout.x.size());
  EnergyBuffers b;
  using plan::BufferRole;
  b.x = plan.add_buffer("x", BufferRole::positions, plan::bytes_of(layout.x));
  b.predicted = plan.add_buffer("predicted", BufferRole::inertia_target, plan::bytes_of(predicted));
  if (!layout.stretch.empty())
    b.stretch = plan.add_buffer("stretch", BufferRole::elements, plan::bytes_of(layout.stretch));
  if (!layout.bend.empty()) b.bend = plan.add_buffer("bend", BufferRole::elements, plan::bytes_of(layout.bend));
  if (!layout.tets.empty()) b.tets = plan.add_buffer("tets", BufferRole::elements, plan::bytes_of(layout.tets));
  b.energy = plan.add_buffer("energy", BufferRole::results,
                             std::vector<std::byte>(static_cast<std::size_t>(where.size) * sizeof(float)));

  // Every element is independent: one task whose launches each cover a
  // whole set.
  std::vector<plan::KernelLaunch> launches;
  plan::KernelLaunch inertia =
      element_launch("energy_inertia", b.x, b.predicted, b.energy, where.inertia_first, plan.particle_count);
  const double hi = inertia_dt(layout, h);  // air drag weighs the inertia (sim_layout.hpp)
  inertia.args.push_back(Arg::of_float(static_cast<float>(1.0 / (hi * hi))));
  launches.push_back(std::move(inertia));
  if (b.stretch >= 0) {
    launches.push_back(element_launch("energy_stretch", b.x, b.stretch, b.energy, where.stretch_first,
                                      static_cast<int>(layout.stretch.size())));
  }
  if (b.bend >= 0) {
    launches.push_back(
        element_launch("energy_bend", b.x, b.bend, b.energy, where.bend_first, static_cast<int>(layout.bend.size())));
  }
  if (b.tets >= 0) {
    launches.push_back(
        element_launch("energy_tet", b.x, b.tets, b.energy, where.tet_first, static_cast<int>(layout.tets.size())));
  }
  plan.add_task(plan::make_task("energy", plan::TaskKind::energy), std::move(launches));
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::energy
