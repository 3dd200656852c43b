#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "solver/energy/element_energies.hpp"
#include "solver/energy/energy_plan.hpp"
#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/moving_cloth.hpp"
#include "solver/energy/moving_soft_box.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "solver/energy/predicted_positions.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

std::vector<float> as_floats(const std::vector<std::byte>& raw) {
  std::vector<float> out(raw.size() / sizeof(float));
  std::memcpy(out.data(), raw.data(), raw.size());
  return out;
}

double sum(const std::vector<float>& v, int first, int last) {
  double s = 0.0;
  for (int i = first; i < last; ++i) s += v[i];
  return s;
}

}  // namespace

TEST_CASE("the device energy kernels equal the host incremental potential on a moving cloth", "[energy]") {
  // Stiff springs (1e4) near rest length: the case where a naive float
  // |xa - xb| - L loses most of its digits.
  const double h = 1.0 / 240.0;
  const SimLayout start = test::moving_cloth(16, 1e4, 1e-2, h);
  const auto predicted = energy::predicted_positions(start, h);
  xpbd::XpbdReference step(start, {h, 8});  // one substep on: x away from x~
  step.substep();
  const SimLayout& state = step.state();

  energy::EnergyBuffers ids;
  const plan::SubstepPlan plan = energy::make_energy_plan(start, predicted, h, &ids);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  exec.write(ids.x, std::as_bytes(std::span(state.x)));  // evaluate the stepped state
  exec.run_substeps(1);
  const std::vector<float> terms = as_floats(exec.read(ids.energy));
  const energy::EnergyOutput where = energy::energy_output(state);
  REQUIRE(int(terms.size()) == where.size);

  // Totals against the double-precision host, term by term.
  const energy::EnergyTerms host =
      energy::energy_terms(energy::make_incremental_potential(state, predicted, h), energy::positions_of(state.x));
  const double inertia = sum(terms, where.inertia_first, where.stretch_first);
  const double stretch = sum(terms, where.stretch_first, where.bend_first);
  const double bend = sum(terms, where.bend_first, where.size);
  INFO("device: inertia " << inertia << " stretch " << stretch << " bend " << bend << "; host: inertia " << host.inertia
                          << " stretch " << host.stretch << " bend " << host.bend);
  REQUIRE(host.inertia > 0.0);
  REQUIRE(host.stretch > 0.0);
  REQUIRE(host.bend > 0.0);
  CHECK(inertia + stretch + bend == Approx(energy::incremental_potential(state, predicted, h)).epsilon(1e-5));
  CHECK(inertia == Approx(host.inertia).epsilon(1e-5));
  CHECK(stretch == Approx(host.stretch).epsilon(1e-5));
  CHECK(bend == Approx(host.bend).epsilon(1e-5));

  // Element by element against the host's float twin of the kernels.
  const std::vector<float> twin = energy::element_energies(state, predicted, h);
  const double largest = *std::max_element(twin.begin(), twin.end());
  double worst = 0.0;
  for (int i = 0; i < where.size; ++i) {
    worst = std::max(worst, std::abs(double(terms[i]) - twin[i]) / (std::abs(twin[i]) + 1e-6 * largest));
  }
  INFO("worst relative difference of one element " << worst);
  CHECK(worst < 1e-5);
}

TEST_CASE("the device energy kernels equal the host incremental potential on a moving soft box", "[energy][tet]") {
  const std::string model = GENERATE("neo_hookean", "stvk");
  const double h = 1.0 / 240.0;
  const SimLayout start = test::moving_soft_box(4, model, 5, 0.05);
  const auto predicted = energy::predicted_positions(start, h);
  SimLayout state = start;  // evaluate another deformed state than x0
  const SimLayout other = test::moving_soft_box(4, model, 6, 0.08);
  state.x = other.x;

  energy::EnergyBuffers ids;
  const plan::SubstepPlan plan = energy::make_energy_plan(start, predicted, h, &ids);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  exec.write(ids.x, std::as_bytes(std::span(state.x)));
  exec.run_substeps(1);
  const std::vector<float> terms = as_floats(exec.read(ids.energy));
  const energy::EnergyOutput where = energy::energy_output(state);
  REQUIRE(int(terms.size()) == where.size);
  REQUIRE(where.tet_first == int(state.x.size()));  // no constraints: particles, then tets

  const energy::EnergyTerms host =
      energy::energy_terms(energy::make_incremental_potential(state, predicted, h), energy::positions_of(state.x));
  const double inertia = sum(terms, where.inertia_first, where.stretch_first);
  const double tet = sum(terms, where.tet_first, where.size);
  INFO(model << " device: inertia " << inertia << " tet " << tet << "; host: inertia " << host.inertia << " tet "
             << host.tet);
  REQUIRE(host.tet > 0.0);
  CHECK(inertia + tet == Approx(energy::incremental_potential(state, predicted, h)).epsilon(1e-5));
  CHECK(inertia == Approx(host.inertia).epsilon(1e-5));
  CHECK(tet == Approx(host.tet).epsilon(1e-5));

  const std::vector<float> twin = energy::element_energies(state, predicted, h);
  const double largest = *std::max_element(twin.begin() + where.tet_first, twin.end());
  double worst = 0.0;
  for (int i = where.tet_first; i < where.size; ++i) {
    worst = std::max(worst, std::abs(double(terms[i]) - twin[i]) / (std::abs(twin[i]) + 1e-6 * largest));
  }
  INFO("worst relative difference of one tet " << worst);
  CHECK(worst < 1e-5);
}
