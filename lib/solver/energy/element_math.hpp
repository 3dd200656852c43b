#pragma once
// The shared element math (kernels/common/energy_*.h) in double precision,
// for the Newton reference and its tests. The headers are written for one
// scalar type per translation unit; this one sets ats_real to double and
// wraps them in a namespace, so its ats_vec3/ats_mat3 (double) are types
// distinct from the float ones of other files (one definition rule).
// A file that includes this cannot also use the float headers.
#include <math.h>

#include <cmath>

#ifdef ATS_MATH_H
#error "solver/energy/element_math.hpp must come before any float include of common/ats_math.h"
#endif

#include "common/collider_types.h" /* float records, one type for every file */

namespace atssim::solver::energy::f64 {
#define ats_real double
#include "common/collider_distance.h"
#include "common/energy_bend_element.h"
#include "common/energy_bending.h"
#include "common/energy_dihedral.h"
#include "common/energy_inertia.h"
#include "common/energy_membrane_stvk.h"
#include "common/energy_spring_damping.h"
#include "common/energy_stretch.h"
#include "common/energy_tet_neohookean.h"
#include "common/energy_tet_stvk.h"
#include "common/self_contact.h"
#undef ats_real
}  // namespace atssim::solver::energy::f64
