#include <catch2/catch.hpp>

#include "solver/jpgd/jpgd_plan.hpp"
#include "solver/vertex_starts.hpp"
#include "support/positions.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

constexpr double kH = 1.0 / 240.0;
constexpr int kSubsteps = 4;

// x and v after kSubsteps of the JPGD plan on the whole CPU device.
std::pair<std::vector<Float4>, std::vector<Float4>> run_plan(const SimLayout& start, vertex::JacobiOrdering ordering,
                                                             double momentum) {
  vertex::VertexBuffers ids;
  jpgd::JpgdSettings settings;
  settings.substep_dt = kH;
  settings.momentum = momentum;
  settings.ordering = ordering;
  const auto plan = jpgd::make_jpgd_plan(start, settings, &ids);
  return test::run_on_cpu(plan, ids, kSubsteps);
}

}  // namespace

TEST_CASE("the JPGD kernel's lanes (vertex_batches) give the vertices' bits", "[jpgd]") {
  // The lanes' gather is the scalar one's operations per lane
  // (common/vertex_system_lanes.h); the bar's 81 vertices end in a padded
  // batch, and its pinned top face takes the lanes' gather unused.
  const std::string scene =
      GENERATE("cloth over the ground", "cloth, half dihedral, damped springs", "neo-Hookean solid");
  const double momentum = GENERATE(0.0, 0.5);  // Chebyshev weights, or heavy-ball momentum
  INFO(scene << ", momentum " << momentum);
  const SimLayout start = test::vertex_start(scene, kH);
  const auto one = run_plan(start, vertex::JacobiOrdering::vertices, momentum);
  const auto lanes = run_plan(start, vertex::JacobiOrdering::vertex_batches, momentum);
  CHECK(test::max_distance(one.first, start.x) > 1e-4);  // it moved
  CHECK(test::same_bits(one, lanes));
}
