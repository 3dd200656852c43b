#include <catch2/catch.hpp>

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

// Runs the hanging cloth for 10 frames on the CPU split into two 1-CU
// sub-devices with the given schedule; returns the output path.
std::string run_cloth(const test::TempDir& dir, const std::string& schedule, const std::string& devices = "cpu/2") {
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(20, 1e4, 1e-3, 6));
  const std::string out = dir.file(schedule + ".h5");
  app::RunOptions options;
  options.scene_path = scene;
  options.overrides = {"output.path=" + out, "simulation.frames=10", "devices=" + devices,
                       "solver.schedule=" + schedule};
  app::run_simulation(options);
  return out;
}

std::vector<double> read_doubles(hid_t file, const char* name) {
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  REQUIRE(set >= 0);
  const hid_t space = H5Dget_space(set);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> v(static_cast<std::size_t>(n));
  if (n > 0) H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(set);
  return v;
}

std::vector<int> read_ints(hid_t file, const char* name) {
  const auto d = read_doubles(file, name);
  return std::vector<int>(d.begin(), d.end());
}

}  // namespace

TEST_CASE("split and heft on two sub-devices give the single-device positions bit for bit after 10 frames", "[fast]") {
  test::TempDir dir;
  const auto single = io::read_frame_positions(run_cloth(dir, "single"), 10);
  for (const std::string schedule : {"split", "heft"}) {
    const std::string out = run_cloth(dir, schedule);
    const auto two = io::read_frame_positions(out, 10);
    REQUIRE(two.size() == single.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < two.size(); ++i) worst = std::max(worst, double(std::abs(two[i] - single[i])));
    INFO(schedule << ": max |difference| " << worst);
    CHECK(two == single);
    // Both sub-devices ran tasks of the recorded frames.
    const hid_t file = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    REQUIRE(file >= 0);
    const auto device = read_ints(file, "/schedule/device");
    H5Fclose(file);
    CHECK(std::count(device.begin(), device.end(), 0) > 0);
    CHECK(std::count(device.begin(), device.end(), 1) > 0);
  }
}

TEST_CASE("every executed schedule's measured order respects the task graph, and every cost is positive") {
  const std::string schedule = GENERATE("single", "split", "heft");
  test::TempDir dir;
  const std::string out = run_cloth(dir, schedule);
  const hid_t file = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const auto from = read_ints(file, "/schedule/tasks/edge_from");
  const auto to = read_ints(file, "/schedule/tasks/edge_to");
  const auto frame = read_ints(file, "/schedule/frame");
  const auto task = read_ints(file, "/schedule/task");
  const auto device = read_ints(file, "/schedule/device");
  const auto start = read_doubles(file, "/schedule/measured_start_ms");
  const auto finish = read_doubles(file, "/schedule/measured_finish_ms");
  const auto costs = read_doubles(file, "/devices/costs_ms");
  H5Fclose(file);
  REQUIRE_FALSE(from.empty());
  REQUIRE(frame.size() == task.size());
  std::size_t tasks = 0;
  for (int t : task) tasks = std::max<std::size_t>(tasks, t + 1);
  CHECK(costs.size() == tasks * 2);
  for (double c : costs) {
    CHECK(std::isfinite(c));
    CHECK(c > 0.0);
  }
  // Per frame: each task ran once, and no task started before a predecessor finished.
  const double tolerance_ms = 1e-3;
  int checked = 0;
  for (int f = 1; f <= 10; ++f) {
    std::vector<double> s(tasks, -1.0), e(tasks, -1.0);
    for (std::size_t r = 0; r < frame.size(); ++r) {
      if (frame[r] != f) continue;
      CHECK(s[task[r]] < 0.0);
      s[task[r]] = start[r];
      e[task[r]] = finish[r];
      CHECK(device[r] >= 0);
      CHECK(device[r] < 2);
    }
    for (std::size_t k = 0; k < from.size(); ++k) {
      REQUIRE(s[to[k]] >= 0.0);
      CHECK(s[to[k]] >= e[from[k]] - tolerance_ms);
      ++checked;
    }
  }
  CHECK(checked == 10 * static_cast<int>(from.size()));
}

TEST_CASE("a two-device schedule on one device is an input error", "[fast]") {
  test::TempDir dir;
  try {
    run_cloth(dir, "heft", "cpu");
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    CHECK(std::string(e.what()).find("cpu/2") != std::string::npos);
  }
}

// Task merging at run time (solver.task_merging; sched/merged_heft.hpp, whose
// choice test_sched checks against makespans worked out by hand): what a run
// records of it. Whether a run merges depends on its profiled costs, so this
// checks what must hold either way, and that `off` merges nothing.
TEST_CASE("a heft run records each task's merged group and the makespan HEFT predicted without merging", "[fast]") {
  test::TempDir dir;
  for (const std::string merging : {"auto", "off"}) {
    const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(20, 1e4, 1e-3, 6));
    const std::string out = dir.file("merge_" + merging + ".h5");
    app::RunOptions options;
    options.scene_path = scene;
    options.overrides = {"output.path=" + out,   "simulation.frames=6",    "devices=cpu/2",
                         "solver.schedule=heft", "solver.executor=events", "solver.task_merging=" + merging};
    app::run_simulation(options);
    const hid_t f = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    REQUIRE(f >= 0);
    const auto frame = read_ints(f, "schedule/frame");
    const auto task = read_ints(f, "schedule/task");
    const auto device = read_ints(f, "schedule/device");
    const auto group = read_ints(f, "schedule/merge_group");
    const auto iteration = read_ints(f, "schedule/tasks/iteration");
    const auto predicted = read_doubles(f, "schedule/makespan/predicted_ms");
    const auto unmerged = read_doubles(f, "schedule/makespan/unmerged_predicted_ms");
    H5Fclose(f);
    INFO("task_merging: " << merging);
    REQUIRE(group.size() == frame.size());
    REQUIRE(unmerged.size() == predicted.size());
    for (double u : unmerged) CHECK(std::isfinite(u));
    // The members of a merged task ran on one device, all of one iteration.
    std::map<std::pair<int, int>, std::pair<int, int>> seen;  // (frame, group) -> (device, iteration)
    for (std::size_t r = 0; r < frame.size(); ++r) {
      if (merging == "off") CHECK(group[r] == -1);
      if (group[r] < 0) continue;
      const auto key = std::make_pair(frame[r], group[r]);
      const auto here = std::make_pair(device[r], iteration.at(static_cast<std::size_t>(task[r])));
      const auto [it, fresh] = seen.emplace(key, here);
      if (!fresh) CHECK(it->second == here);
    }
  }
}

TEST_CASE("a single-device run records no merges and no unmerged makespan", "[fast]") {
  test::TempDir dir;
  const std::string out = run_cloth(dir, "single", "cpu");
  const hid_t f = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const auto group = read_ints(f, "schedule/merge_group");
  const auto unmerged = read_doubles(f, "schedule/makespan/unmerged_predicted_ms");
  H5Fclose(f);
  REQUIRE_FALSE(group.empty());
  for (int g : group) CHECK(g == -1);
  for (double u : unmerged) CHECK(std::isnan(u));
}
