/* Compiles every material header (kernels/common/energy_tet_*.h,
 * energy_membrane_stvk.h, energy_dihedral.h) into one program and evaluates
 * one element of each (solids/materials_check.h), so a test can compare the
 * device results with the same math compiled for the host. One work-item. */
#include "common/task.h"
#include "solids/materials_check.h"

ATS_TASK void materials_check(int i, __global const float* in, __global float* out) {
  if (i != 0) return;
  float in_p[ATS_MATERIALS_IN];
  float out_p[ATS_MATERIALS_OUT];
  for (int i = 0; i < ATS_MATERIALS_IN; ++i) in_p[i] = in[i];
  ats_materials_check(in_p, out_p);
  for (int i = 0; i < ATS_MATERIALS_OUT; ++i) out[i] = out_p[i];
}
