#include "solver/energy/energy_plan.hpp"

#include <cstring>

#include <fmt/format.h>

#include "solver/energy/finite_stiffness.hpp"
#include "util/error.hpp"

namespace atssim::solver::energy {

namespace {

using Arg = KernelArg;

// (out_first, first, count) follow the three buffers: the range is args 4, 5.
KernelLaunch element_launch(const char* kernel, BufferId x, BufferId elements, BufferId out, int out_first, int count) {
  return {kernel,
          static_cast<std::size_t>(count),
          {Arg::of_buffer(x), Arg::of_buffer(elements), Arg::of_buffer(out), Arg::of_int(out_first), Arg::of_int(0),
           Arg::of_int(count)},
          4};
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

SubstepPlan make_energy_plan(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                             EnergyBuffers* ids) {
  if (predicted.size() != layout.x.size()) {
    throw input_error(
        fmt::format("energy plan: {} predicted positions for {} particles", predicted.size(), layout.x.size()));
  }
  require_finite_stiffness(layout);  // the device would compute inf or NaN
  require_valid_tets(layout);
  const EnergyOutput where = energy_output(layout);

  SubstepPlan plan;
  plan.program = "xpbd_energy";
  plan.particle_count = static_cast<int>(layout.x.size());
  EnergyBuffers b;
  b.x = plan.add_buffer("x", bytes_of(layout.x));
  b.predicted = plan.add_buffer("predicted", bytes_of(predicted));
  if (!layout.stretch.empty()) b.stretch = plan.add_buffer("stretch", bytes_of(layout.stretch));
  if (!layout.bend.empty()) b.bend = plan.add_buffer("bend", bytes_of(layout.bend));
  if (!layout.tets.empty()) b.tets = plan.add_buffer("tets", bytes_of(layout.tets));
  b.energy = plan.add_buffer("energy", std::vector<std::byte>(static_cast<std::size_t>(where.size) * sizeof(float)));
  plan.positions = b.x;

  // Every element is independent, so one task whose launches each cover a
  // whole set; range_arg lets split_plan cut them between devices.
  std::vector<KernelLaunch> launches;
  KernelLaunch inertia =
      element_launch("energy_inertia", b.x, b.predicted, b.energy, where.inertia_first, plan.particle_count);
  inertia.args.push_back(Arg::of_float(static_cast<float>(1.0 / (h * h))));
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
  plan.add_task({"energy", "energy", -1, -1}, std::move(launches));
  if (ids != nullptr) *ids = b;
  return plan;
}

}  // namespace atssim::solver::energy
