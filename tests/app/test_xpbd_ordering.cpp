// solver.ordering (XPBD): colors, color_batches or NvCloth's simd batches, end to end.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "support/scene_runs.hpp"
#include "support/scenes.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

std::string cloth_with(const std::string& solver_keys) {
  return test::hanging_cloth_yaml(16, 1e4, 1e-3, 8) + "solver:\n" + solver_keys;
}

// The input error a run of `yaml` under `schedule` raises ("" when it runs).
std::string input_error_of(const std::string& yaml, const std::string& schedule) {
  test::TempDir dir;
  app::RunOptions o = test::options(dir, yaml, "xpbd", schedule);
  o.overrides.push_back("simulation.frames=1");
  try {
    app::run_simulation(o);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::input);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a cloth hangs alike under the colors and the batches ordering") {
  test::TempDir dir;
  std::vector<std::vector<Eigen::Vector3d>> last;
  for (const std::string ordering : {"colors", "batches"}) {
    const std::string out = ordering + ".h5";
    app::RunOptions o = test::options(dir, cloth_with("  ordering: " + ordering + "\n"), "xpbd", "single", out);
    app::run_simulation(o);
    last.push_back(test::frame(dir.file(out), io::read_summary(dir.file(out)).frames - 1));
  }
  const Eigen::Vector3d pinned_before(-0.5, 0.0, -0.5);
  double largest = 0.0, lowest = 0.0;
  for (std::size_t i = 0; i < last[0].size(); ++i) {
    largest = std::max(largest, (last[0][i] - last[1][i]).norm());
    lowest = std::min({lowest, last[0][i].y(), last[1][i].y()});
  }
  INFO("largest difference " << largest << " m on a 1 m cloth; lowest point " << lowest << " m");
  CHECK(lowest < -0.1);         // both fell: 10 frames at 60 fps, pinned at two corners
  CHECK(largest < 0.01);        // within 1 % of the cloth's size
  CHECK(largest > 0.0);         // yet another Gauss-Seidel order
  for (const auto& x : last) {  // the pinned corner did not move
    double nearest = 1.0;
    for (const auto& p : x) nearest = std::min(nearest, (p - pinned_before).norm());
    CHECK(nearest < 1e-6);
  }
}

TEST_CASE("color_batches: the same bits on one device and cut over two, within 1e-4 m of the colors") {
  // A hanging cloth (springs and bending stencils) and a hanging StVK bar (tets).
  const std::string body = GENERATE(std::string("cloth"), std::string("bar"));
  const auto scene_with = [&](const std::string& keys) {
    return body == "cloth" ? cloth_with(keys) : test::stvk_bar_yaml(2) + "solver:\n" + keys;
  };
  test::TempDir dir;
  std::vector<std::vector<Eigen::Vector3d>> last;
  const std::vector<std::pair<std::string, std::string>> runs{
      {"colors", "single"}, {"color_batches", "single"}, {"color_batches", "split"}, {"color_batches", "heft"}};
  for (const auto& [ordering, schedule] : runs) {
    std::string out = ordering;
    out += "_" + schedule + ".h5";
    app::RunOptions o = test::options(dir, scene_with("  ordering: " + ordering + "\n"), "xpbd", schedule, out);
    app::run_simulation(o);
    last.push_back(test::frame(dir.file(out), io::read_summary(dir.file(out)).frames - 1));
  }
  const auto largest = [&](std::size_t a, std::size_t b) {
    double d = 0.0;
    for (std::size_t i = 0; i < last[a].size(); ++i) d = std::max(d, (last[a][i] - last[b][i]).norm());
    return d;
  };
  INFO(body << ": color_batches against colors: " << largest(0, 1) << " m after 10 frames");
  CHECK(largest(1, 2) == 0.0);  // split: every color block's batches cut between the sub-devices
  CHECK(largest(1, 3) == 0.0);  // heft
  // The color order with float8 lanes: only rounding differs from the scalar
  // lanes (the batches ordering, another Gauss-Seidel order, is ~1e-3 away).
  CHECK(largest(0, 1) < 1e-4);
}

TEST_CASE("ordering batches with a two-device schedule is an input error at its line") {
  const std::string schedule = GENERATE("split", "heft", "async");
  const std::string what = input_error_of(cloth_with("  ordering: batches\n"), schedule);
  INFO(what);
  CHECK(what.find("scene.yaml:") != std::string::npos);
  CHECK(what.find("solver.ordering 'batches'") != std::string::npos);
  CHECK(what.find("schedule '" + schedule + "'") != std::string::npos);
  CHECK(input_error_of(cloth_with("  ordering: colors\n"), schedule).empty());
}

TEST_CASE("an unknown ordering is an input error naming the key") {
  const std::string what = input_error_of(cloth_with("  ordering: stripes\n"), "single");
  INFO(what);
  CHECK(what.find("solver.ordering is 'stripes'") != std::string::npos);
  CHECK(what.find("colors, color_batches or batches") != std::string::npos);
}
