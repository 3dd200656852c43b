// The paper's five scenes at the paper's size run a frame through the real
// binary: one substep of one iteration (`--set`), on the whole CPU device,
// from meshes written for the test (tests/support/paper_scenes.hpp). Their
// own 32-64 substeps x 8-12 iterations a frame cost minutes at this size;
// this short frame costs 6-19 s per scene on two cores (kernels built,
// tasks profiled, contact lists built over 69-150 K vertices). The ctest
// label paper_size runs them alone (`ctest --test-dir build/release -L
// paper_size`); the release preset runs them, the sanitizer presets do not.
// scripts/bench_paper_scenes.py runs them at their own settings.
// tests/check_doc_counts.py (in the presets) fails when a scenes/paper/NAME.yaml
// has no case "the paper's NAME at the paper's size runs a frame" here.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "io/result_reader.hpp"
#include "support/cli_runs.hpp"
#include "support/paper_scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

void run_one_frame(const std::string& name) {
  test::TempDir dir;
  const auto paper = test::paper_scene_copy(dir);
  const std::string out = dir.file("out.h5");
  const auto r = test::run_atssim(dir, "run " + (paper / (name + ".yaml")).string() + " -o " + out +
                                           " --frames 1 --devices cpu --quiet --set simulation.substeps=1"
                                           " --set simulation.iterations=1");
  INFO(name << ": " << r.err);
  REQUIRE(r.code == 0);
  const auto summary = io::read_summary(out);
  CHECK(summary.complete);
  CHECK(summary.frames == 2);
  CHECK(summary.particles == static_cast<std::size_t>(test::stated_size(name, false).vertices));
  for (float v : io::read_frame_positions(out, 1)) REQUIRE(std::isfinite(v));
}

}  // namespace

TEST_CASE("the paper's dress at the paper's size runs a frame", "[paper_size]") { run_one_frame("dress"); }
TEST_CASE("the paper's jersey at the paper's size runs a frame", "[paper_size]") { run_one_frame("jersey"); }
TEST_CASE("the paper's pillows at the paper's size runs a frame", "[paper_size]") { run_one_frame("pillows"); }
TEST_CASE("the paper's funnel at the paper's size runs a frame", "[paper_size]") { run_one_frame("funnel"); }
TEST_CASE("the paper's letters at the paper's size runs a frame", "[paper_size]") { run_one_frame("letters"); }
