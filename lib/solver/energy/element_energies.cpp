#include "solver/energy/element_energies.hpp"

#include "common/energy_bending.h"
#include "common/energy_inertia.h"
#include "common/energy_stretch.h"
#include "solver/energy/energy_plan.hpp"

namespace atssim::solver::energy {

namespace {
ats_vec3 xyz(const xpbd::Float4& p) { return ats_v3(p.x, p.y, p.z); }
}  // namespace

std::vector<float> element_energies(const xpbd::XpbdLayout& layout, const std::vector<xpbd::Float4>& predicted,
                                    double h) {
  const EnergyOutput where = energy_output(layout);
  std::vector<float> out(where.size, 0.0f);
  // As the kernel gets it: 1/h^2 rounded to float once.
  const float inv_h2 = static_cast<float>(1.0 / (h * h));
  for (std::size_t i = 0; i < layout.x.size(); ++i) {
    const xpbd::Float4& p = layout.x[i];
    if (p.w > 0.0f) out[where.inertia_first + i] = ats_inertia_energy(xyz(p), xyz(predicted[i]), 1.0f / p.w, inv_h2);
  }
  for (std::size_t i = 0; i < layout.stretch.size(); ++i) {
    const ats_distance_c& c = layout.stretch[i];
    out[where.stretch_first + i] =
        ats_stretch_energy(xyz(layout.x[c.a]), xyz(layout.x[c.b]), c.rest, 1.0f / c.compliance);
  }
  for (std::size_t i = 0; i < layout.bend.size(); ++i) {
    const ats_bend_c& c = layout.bend[i];
    ats_vec3 q[4];
    for (int j = 0; j < 4; ++j) q[j] = xyz(layout.x[c.v[j]]);
    out[where.bend_first + i] = ats_bend_energy(q, c.K, c.scale, 1.0f / c.compliance);
  }
  return out;
}

}  // namespace atssim::solver::energy
