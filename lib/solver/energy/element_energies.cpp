#include "solver/energy/element_energies.hpp"

#include "common/energy_bend_element.h"
#include "common/energy_inertia.h"
#include "common/energy_stretch.h"
#include "common/energy_tet_neohookean.h"
#include "common/energy_tet_stvk.h"
#include "solver/energy/energy_plan.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace atssim::solver::energy {

namespace {
ats_vec3 xyz(const Float4& p) { return ats_v3(p.x, p.y, p.z); }

// body(i) for i in [0, count) on TBB's threads: every term is written by
// its own index, so the values do not depend on the split.
template <typename Body>
void each(std::size_t count, Body&& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
  });
}
}  // namespace

std::vector<float> element_energies(const SimLayout& layout, const std::vector<Float4>& predicted, double h) {
  const EnergyOutput where = energy_output(layout);
  std::vector<float> out(where.size, 0.0f);
  // As the kernel gets it: 1/h^2 rounded to float once.
  const double hi = inertia_dt(layout, h);  // air drag weighs the inertia (sim_layout.hpp)
  const float inv_h2 = static_cast<float>(1.0 / (hi * hi));
  each(layout.x.size(), [&](std::size_t i) {
    const Float4& p = layout.x[i];
    if (p.w > 0.0f) out[where.inertia_first + i] = ats_inertia_energy(xyz(p), xyz(predicted[i]), 1.0f / p.w, inv_h2);
  });
  each(layout.stretch.size(), [&](std::size_t i) {
    const ats_distance_c& c = layout.stretch[i];
    out[where.stretch_first + i] =
        ats_stretch_energy(xyz(layout.x[c.a]), xyz(layout.x[c.b]), c.rest, 1.0f / c.compliance);
  });
  each(layout.bend.size(), [&](std::size_t i) {
    const ats_bend_c& c = layout.bend[i];
    ats_vec3 q[4];
    for (int j = 0; j < 4; ++j) q[j] = xyz(layout.x[c.v[j]]);
    out[where.bend_first + i] = ats_bend_element_energy(c.model, q, c.K, c.scale, 1.0f / c.compliance, c.rest_angle);
  });
  each(layout.tets.size(), [&](std::size_t i) {
    const ats_tet_c& t = layout.tets[i];
    ats_vec3 q[4];
    for (int j = 0; j < 4; ++j) q[j] = xyz(layout.x[t.v[j]]);
    ats_mat3 dm_inv;
    for (int r = 0; r < 3; ++r) dm_inv.r[r] = ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
    out[where.tet_first + i] = t.model == ATS_TET_STVK ? ats_tet_stvk_energy(q, dm_inv, t.volume, t.mu, t.lambda)
                                                       : ats_tet_nh_energy(q, dm_inv, t.volume, t.mu, t.lambda);
  });
  return out;
}

}  // namespace atssim::solver::energy
