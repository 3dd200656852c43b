#include "solver/method_plan.hpp"

#include <array>

#include <fmt/format.h>

#include "solver/jpgd/jpgd_plan.hpp"
#include "solver/sosd/sosd_plan.hpp"
#include "solver/vbd/vbd_plan.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "util/error.hpp"

namespace atssim::solver {

namespace {
constexpr std::array<std::string_view, 4> kMethods{"xpbd", "vbd", "sosd", "jpgd"};
}

std::span<const std::string_view> method_names() { return kMethods; }

// SOSD is hybrid: its Gauss-Seidel part is the main block's precedence in
// one combine step per iteration; its stencil solves are Jacobi sweeps.
bool is_gauss_seidel(const std::string& method) { return method == "xpbd" || method == "vbd"; }

plan::SubstepPlan make_method_plan(const std::string& method, const SimLayout& layout, double substep_dt,
                                   int iterations, const MethodOptions& options) {
  if (method == "xpbd") return xpbd::make_xpbd_plan(layout, {substep_dt, iterations});
  if (method == "vbd") return vbd::make_vbd_plan(layout, substep_dt, iterations);
  if (method == "sosd") return sosd::make_sosd_plan(layout, substep_dt, iterations, options.stencil_step);
  if (method == "jpgd")
    return jpgd::make_jpgd_plan(layout,
                                {substep_dt, iterations, options.chebyshev_rho, options.jacobi_step, options.momentum});
  throw input_error(fmt::format("unknown method '{}'; available: xpbd, vbd, sosd, jpgd", method));
}

}  // namespace atssim::solver
