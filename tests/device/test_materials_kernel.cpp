// The material headers (kernels/common/energy_tet_*.h, energy_membrane_stvk.h,
// energy_dihedral.h) compiled by the OpenCL compiler agree with the same
// headers compiled for the host in float (kernels/solids/materials_check.h).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <vector>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "plan/substep_plan.hpp"
#include "solids/materials_check.h"  // float: ats_real is float here

using namespace atssim;

namespace {

void put(std::vector<float>& in, int at, ats_vec3 v) {
  in[at] = v.x;
  in[at + 1] = v.y;
  in[at + 2] = v.z;
}

// One deformed element of each kind, in the layout of materials_check.h.
std::vector<float> check_inputs() {
  std::vector<float> in(ATS_MATERIALS_IN, 0.0f);
  const ats_vec3 tet_rest[4] = {ats_v3(0, 0, 0), ats_v3(1.1f, 0.1f, 0), ats_v3(0.2f, 0.9f, -0.1f),
                                ats_v3(0.1f, 0.2f, 1.2f)};
  const ats_tet_rest tr = ats_tet_rest_of(tet_rest);
  const ats_vec3 tet[4] = {ats_v3(0.1f, 0, 0), ats_v3(1.3f, 0.2f, 0.1f), ats_v3(0.1f, 0.7f, 0.2f),
                           ats_v3(0.3f, 0.1f, 0.9f)};
  for (int a = 0; a < 4; ++a) put(in, 3 * a, tet[a]);
  for (int i = 0; i < 3; ++i) put(in, 12 + 3 * i, tr.dm_inv.r[i]);
  in[21] = tr.volume;
  in[22] = 0.4f;  // mu
  in[23] = 0.9f;  // lambda

  const ats_vec3 tri_rest[3] = {ats_v3(0, 0, 0), ats_v3(1, 0, 0.1f), ats_v3(0.3f, 0.8f, 0)};
  const ats_membrane_rest mr = ats_membrane_rest_of(tri_rest);
  const ats_vec3 tri[3] = {ats_v3(0, 0.1f, 0), ats_v3(1.2f, 0, 0.3f), ats_v3(0.2f, 0.7f, 0.2f)};
  for (int a = 0; a < 3; ++a) put(in, 24 + 3 * a, tri[a]);
  in[33] = mr.dm_inv.a00;
  in[34] = mr.dm_inv.a01;
  in[35] = mr.dm_inv.a10;
  in[36] = mr.dm_inv.a11;
  in[37] = mr.area;
  in[38] = 0.7f;
  in[39] = 0.3f;

  const ats_vec3 stencil[4] = {ats_v3(0, 0, 0), ats_v3(1, 0, 0), ats_v3(0.5f, 0.8f, 0.5f), ats_v3(0.4f, -0.9f, 0.2f)};
  for (int a = 0; a < 4; ++a) put(in, 40 + 3 * a, stencil[a]);
  in[52] = 0.1f;
  in[53] = ats_dihedral_rest_stiffness(stencil, 0.05f);
  return in;
}

const char* const k_material[4] = {"neo-Hookean tet", "StVK tet", "StVK membrane", "dihedral"};
const char* const k_part[4] = {"energy", "gradient", "H_01", "H_00 (PSD)"};
const int k_part_first[5] = {0, 1, 13, 22, ATS_MATERIALS_RECORD};

}  // namespace

TEST_CASE("the material kernels on the device equal the host float math to 1e-4", "[energy][materials]") {
  const std::vector<float> in = check_inputs();
  std::vector<float> host(ATS_MATERIALS_OUT);
  ats_materials_check(in.data(), host.data());

  plan::SubstepPlan plan;
  plan.program = "materials_check";
  const plan::BufferId in_id = plan.add_buffer("in", plan::BufferRole::elements, plan::bytes_of(in));
  const plan::BufferId out_id =
      plan.add_buffer("out", plan::BufferRole::results, std::vector<std::byte>(ATS_MATERIALS_OUT * sizeof(float)));
  plan.add_task(
      plan::make_task("materials", plan::TaskKind::energy),
      {{"materials_check", {0, 1}, {plan::KernelArg::of_buffer(in_id), plan::KernelArg::of_buffer(out_id)}, {}}});
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  exec.run_substeps(1);
  const std::vector<std::byte> raw = exec.read(out_id);
  REQUIRE(raw.size() == ATS_MATERIALS_OUT * sizeof(float));
  std::vector<float> dev(ATS_MATERIALS_OUT);
  std::memcpy(dev.data(), raw.data(), raw.size());

  for (int m = 0; m < 4; ++m) {
    for (int p = 0; p < 4; ++p) {
      const int first = m * ATS_MATERIALS_RECORD + k_part_first[p],
                last = m * ATS_MATERIALS_RECORD + k_part_first[p + 1];
      // Relative to the largest value of the part: a Hessian entry may be ~0.
      double scale = 0.0, worst = 0.0;
      for (int i = first; i < last; ++i) scale = std::max(scale, double(std::abs(host[i])));
      for (int i = first; i < last; ++i) worst = std::max(worst, double(std::abs(dev[i] - host[i])));
      INFO(k_material[m] << " " << k_part[p] << ": largest " << scale << ", worst difference " << worst);
      CHECK(scale > 0.0);  // every part does work
      CHECK(std::isfinite(scale));
      CHECK(worst <= 1e-4 * scale);
    }
  }
}

TEST_CASE("project_psd clamps a negative eigenvalue in float", "[energy][materials]") {
  // R diag(3, -1, 2) R^T with R a rotation about (1, 1, 1) / sqrt 3 by 90 degrees.
  const float c = 1.0f / 3.0f, s = 1.0f / std::sqrt(3.0f);
  const ats_mat3 R = {{ats_v3(c, c - s, c + s), ats_v3(c + s, c, c - s), ats_v3(c - s, c + s, c)}};
  const float l[3] = {3.0f, -1.0f, 2.0f};
  ats_mat3 m = ats_m3_diag(0), expected = ats_m3_diag(0);
  for (int e = 0; e < 3; ++e) {
    const ats_vec3 v = ats_v3(R.r[0].x * (e == 0) + R.r[0].y * (e == 1) + R.r[0].z * (e == 2),
                              R.r[1].x * (e == 0) + R.r[1].y * (e == 1) + R.r[1].z * (e == 2),
                              R.r[2].x * (e == 0) + R.r[2].y * (e == 1) + R.r[2].z * (e == 2));
    m = ats_m3_add(m, ats_m3_outer(v, ats_scale(v, l[e])));
    expected = ats_m3_add(expected, ats_m3_outer(v, ats_scale(v, std::max(l[e], 0.0f))));
  }
  const ats_mat3 p = ats_m3_project_psd(m);
  const ats_mat3 d = ats_m3_sub(p, expected);
  CHECK(std::sqrt(ats_m3_ddot(d, d)) <= 1e-5f * 3.0f);
}
