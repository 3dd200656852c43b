#include "solver/method_plan.hpp"

#include <array>

#include <fmt/format.h>

#include "solver/jpgd/jpgd_plan.hpp"
#include "solver/vbd/vbd_plan.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "util/error.hpp"

namespace atssim::solver {

namespace {
constexpr std::array<std::string_view, 3> kMethods{"xpbd", "vbd", "jpgd"};
}

std::span<const std::string_view> method_names() { return kMethods; }

bool is_gauss_seidel(const std::string& method) { return method != "jpgd"; }

SubstepPlan make_method_plan(const std::string& method, const xpbd::XpbdLayout& layout, double substep_dt,
                             int iterations, const MethodOptions& options) {
  if (method == "xpbd") return xpbd::make_xpbd_plan(layout, {substep_dt, iterations});
  if (method == "vbd") return vbd::make_vbd_plan(layout, substep_dt, iterations);
  if (method == "jpgd") return jpgd::make_jpgd_plan(layout, {substep_dt, iterations, options.chebyshev_rho, options.jacobi_step});
  throw input_error(fmt::format("unknown method '{}'; available: xpbd, vbd, jpgd", method));
}

}  // namespace atssim::solver
