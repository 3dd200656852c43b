#include <catch2/catch.hpp>

#include "solver/sosd/sosd_plan.hpp"
#include "solver/vertex_starts.hpp"
#include "support/positions.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

constexpr double kH = 1.0 / 240.0;
constexpr int kIterations = 8;
constexpr int kSubsteps = 4;

// x and v after kSubsteps of the SOSD plan on the whole CPU device.
std::pair<std::vector<Float4>, std::vector<Float4>> run_plan(const SimLayout& start, sosd::SosdOrdering ordering) {
  vertex::VertexBuffers ids;
  const auto plan = sosd::make_sosd_plan(start, kH, kIterations, 0.7, &ids, ordering);
  return test::run_on_cpu(plan, ids, kSubsteps);
}

}  // namespace

TEST_CASE("the SOSD bending stencils' lanes (color_batches) give the colors' bits", "[sosd]") {
  // Each lane fills its 12 x 12 system with the scalar code, then the
  // Cholesky and the substitutions run as 8-float vectors with the scalar
  // operations in the scalar order (kernels/sosd/sosd.cl sosd_bend_lanes);
  // the cloth's pinned corners take the pinned rows, and each color block's
  // last batch is padded.
  const std::string scene = GENERATE("cloth over the ground", "cloth, half dihedral, damped springs");
  INFO(scene);
  const SimLayout start = test::vertex_start(scene, kH);
  const auto colors = run_plan(start, sosd::SosdOrdering::colors);
  const auto lanes = run_plan(start, sosd::SosdOrdering::color_batches);
  CHECK(test::max_distance(colors.first, start.x) > 1e-4);  // it moved
  CHECK(test::same_bits(colors, lanes));
}
