#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <hdf5.h>

#include "io/result_reader.hpp"
#include "support/cli_runs.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

using test::Outcome;
using test::run_atssim;
using test::slurp;

int lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace

TEST_CASE("atssim run writes a complete HDF5 file with every frame", "[fast]") {
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(12));
  const auto r = run_atssim(dir, "run " + scene + " -o " + dir.file("out.h5") + " --frames 3 --devices cpu");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());  // no progress line when stderr is not a terminal
  CHECK(r.out.find("wrote") != std::string::npos);
  const auto s = io::read_summary(dir.file("out.h5"));
  CHECK(s.complete);
  CHECK(s.frames == 4);  // the initial state + 3 frames
  CHECK(s.particles == 144);
  CHECK(std::filesystem::exists(dir.file("out.xdmf")));

  const auto inspect = run_atssim(dir, "inspect " + dir.file("out.h5"));
  CHECK(inspect.code == 0);
  CHECK(inspect.out.find("status:    complete") != std::string::npos);
  CHECK(inspect.out.find("frames:    4") != std::string::npos);
  CHECK(run_atssim(dir, "inspect " + dir.file("nothing.h5")).code == 2);
}

namespace {

// Every bundled scene in scenes/, found on disk, so that a scene added there
// is run here too. The small variants of the paper's scenes
// (scenes/paper/*_small.yaml, minutes a frame at this size on two cores)
// run in tests/app/test_paper_scenes.cpp, one test case each
// (tests/check_doc_counts.py checks that each has one).
std::vector<std::string> bundled_scenes() {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(ATSSIM_SOURCE_DIR) / "scenes")) {
    if (e.path().extension() == ".yaml") found.push_back(e.path().filename().string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace

TEST_CASE("every bundled scene runs") {
  const std::vector<std::string> scenes = bundled_scenes();
  REQUIRE(scenes.size() > 5);  // a wrong root would find none (tests/check_doc_counts.py counts them for the README)
  for (const std::string& scene : scenes) {
    INFO(scene);
    test::TempDir dir;
    const auto r = run_atssim(dir, std::string("run ") + ATSSIM_SOURCE_DIR + "/scenes/" + scene + " -o " +
                                       dir.file("out.h5") + " --frames 1 --quiet");
    INFO(r.err);
    CHECK(r.code == 0);
    CHECK(r.out.empty());
    const auto summary = io::read_summary(dir.file("out.h5"));
    CHECK(summary.complete);
    CHECK(summary.frames == 2);
    for (float v : io::read_frame_positions(dir.file("out.h5"), 1)) REQUIRE(std::isfinite(v));
  }
}

TEST_CASE("a bad scene gives one line naming file and line, exit code 2, and no output file", "[fast]") {
  test::TempDir dir;
  const std::string scene = dir.write("bad.yaml",
                                      "objects:\n  - grid: {size: [1, 1], resolution: [4, 4]}\n"
                                      "    materal: {density: 1}\n");
  const auto r = run_atssim(dir, "run " + scene + " -o " + dir.file("out.h5"));
  CHECK(r.code == 2);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find(scene + ":3:") != std::string::npos);
  CHECK(r.err.find("did you mean 'material'?") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("out.h5")));
}

TEST_CASE("bad usage gives one line and exit code 2", "[fast]") {
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(4));
  for (const std::string& args :
       {"run " + dir.file("missing.yaml"), "run " + scene + " --devices gpu9", "run " + scene + " --frobnicate",
        "run " + scene + " --set nokey", std::string("fly")}) {
    const auto r = run_atssim(dir, args);
    INFO(args << ": " << r.err);
    CHECK(r.code == 2);
    CHECK(lines(r.err) == 1);
  }
}

TEST_CASE("help works for every subcommand", "[fast]") {
  test::TempDir dir;
  for (const char* args :
       {"--help", "run --help", "devices --help", "schedule --help", "converge --help", "inspect --help"}) {
    const auto r = run_atssim(dir, args);
    CHECK(r.code == 0);
    CHECK(r.out.find("Usage") != std::string::npos);
  }
}

TEST_CASE("atssim devices lists the pocl CPU device with its SVM capabilities", "[fast]") {
  test::TempDir dir;
  const auto r = run_atssim(dir, "devices");
  CHECK(r.code == 0);
  CHECK(r.out.find("cpu") != std::string::npos);
  CHECK(r.out.find("SVM coarse") != std::string::npos);
  CHECK(r.out.find("0 (0:0)") != std::string::npos);  // index and platform:device, both accepted by --devices
}

TEST_CASE("a run that blows up exits 1 naming the frame and keeps the frames before it") {
  test::TempDir dir;
  // Block-Jacobi descent with stiffness 1e30, full steps and heavy momentum
  // over 10 s frames overflows float32 in the first frame.
  const std::string scene =
      dir.write("wild.yaml",
                "simulation: {dt: 10, substeps: 1, iterations: 20, frames: 3, gravity: [0, "
                "-1000000, 0]}\n"
                "objects:\n"
                "  - name: cloth\n"
                "    grid: {size: [1, 1], resolution: [6, 6]}\n"
                "    material: {density: 0.2, stretch_stiffness: 1.0e30, bend_stiffness: 1.0e20}\n"
                "    pins: {vertices: [0, 5]}\n"
                "solver: {method: jpgd, jacobi_step: 1, momentum: 0.999}\n");
  const auto r = run_atssim(dir, "run " + scene + " -o " + dir.file("out.h5") + " --devices cpu");
  CHECK(r.code == 1);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find("frame 1") != std::string::npos);
  CHECK(r.err.find("non-finite") != std::string::npos);
  CHECK(r.err.find("1 frames kept") != std::string::npos);
  const auto s = io::read_summary(dir.file("out.h5"));
  CHECK_FALSE(s.complete);
  CHECK(s.frames == 1);
  CHECK(s.error.find("blew up") != std::string::npos);
}

TEST_CASE("a scene far from the origin falling freely is no blow-up", "[fast]") {
  test::TempDir dir;
  // 10 s frames under 1e5 m/s² carry the cloth 5e6 m in the first frame:
  // free fall, what gravity and the time step allow (the old |x| > 1e6 m
  // box called it a blow-up); placed at y = 2e6 m it is fine too.
  std::string cloth = test::hanging_cloth_yaml(6);
  cloth = cloth.substr(cloth.find("objects:"));
  cloth.replace(cloth.find("    pins:"), std::string::npos, "    transform: {translate: [0, 2.0e6, 0]}\n");
  const std::string scene =
      dir.write("far.yaml", "simulation: {dt: 10, substeps: 1, frames: 3, gravity: [0, -100000, 0]}\n" + cloth);
  const auto r = run_atssim(dir, "run " + scene + " -o " + dir.file("out.h5") + " --devices cpu");
  INFO(r.err);
  CHECK(r.code == 0);
  const auto last = io::read_frame_positions(dir.file("out.h5"), 3);
  CHECK(last[1] < 2.0e6 - 1.0e6);  // it fell
}

TEST_CASE("a run killed mid-way leaves a readable file with the frames flushed before the kill", "[fast]") {
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(24));
  const std::string out = dir.file("out.h5");
  const std::string cmd = std::string(ATSSIM_BINARY) + " run " + scene + " -o " + out +
                          " --frames 100000 --quiet >/dev/null 2>&1 & echo $! > " + dir.file("pid");
  REQUIRE(std::system(cmd.c_str()) == 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const int pid = std::stoi(slurp(dir.file("pid")));
  // Wait until a few frames are on disk, then kill without warning.
  std::size_t frames = 0;
  for (int i = 0; i < 200 && frames < 3; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    try {
      frames = io::read_summary(out).frames;
    } catch (...) {
    }
  }
  ::kill(pid, SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  REQUIRE(frames >= 3);
  const auto s = io::read_summary(out);
  CHECK_FALSE(s.complete);
  CHECK(s.frames >= frames);
  const auto last = io::read_frame_positions(out, s.frames - 1);
  CHECK(last.size() == 24 * 24 * 3);
}

TEST_CASE("atssim schedule prints the substep graph, its costs as CSV, and schedules from that CSV", "[fast]") {
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(16, 1e4, 0.0, 2));
  const auto table = run_atssim(dir, "schedule " + scene + " --devices cpu/2 --schedule heft");
  INFO(table.err);
  REQUIRE(table.code == 0);
  CHECK(table.out.find("schedule 'heft' on 2 device(s)") != std::string::npos);
  CHECK(table.out.find("it2/stretch/c0#1") != std::string::npos);
  CHECK(table.out.find("bend") == std::string::npos);  // bending stiffness 0: no bending task

  const auto csv = run_atssim(dir, "schedule " + scene + " --devices cpu/2 --schedule heft --csv");
  REQUIRE(csv.code == 0);
  const std::string costs = dir.write("costs.csv", csv.out);
  const auto json = run_atssim(dir, "schedule " + scene + " --schedule heft --costs " + costs + " --json");
  REQUIRE(json.code == 0);
  CHECK(json.out.find("\"makespan_ms\"") != std::string::npos);
  CHECK(json.out.find("\"waits\"") != std::string::npos);
  const auto dot = run_atssim(dir, "schedule " + scene + " --schedule split --costs " + costs + " --dot");
  REQUIRE(dot.code == 0);
  CHECK(dot.out.find("digraph substep") == 0);
}

TEST_CASE("a cost file that does not match the scene is an input error with its line", "[fast]") {
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(8, 1e4, 0.0, 1));
  const std::string costs = dir.write("costs.csv", "latency_ms,0.01\npredict#0,1,1\nnot_a_task,1,1\n");
  const auto r = run_atssim(dir, "schedule " + scene + " --schedule heft --costs " + costs);
  CHECK(r.code == 2);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find(costs + ":3:") != std::string::npos);
  CHECK(r.err.find("not_a_task") != std::string::npos);
}

TEST_CASE("a split from a cost table of unequal devices drops the parts that round to nothing") {
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(16, 1e4, 0.0, 2));
  const auto csv = run_atssim(dir, "schedule " + scene + " --devices cpu/2 --schedule heft --csv");
  REQUIRE(csv.code == 0);
  // Device 1 three times slower: every block is cut 3:1 instead of 1:1, so
  // some small blocks keep a single part.
  std::string unequal;
  std::stringstream in(csv.out);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line.rfind("task", 0) == 0 || line.rfind("latency", 0) == 0) {
      unequal += line + "\n";
      continue;
    }
    unequal += line.substr(0, line.find(',')) + ",1,3\n";
  }
  const auto r = run_atssim(dir, "schedule " + scene + " --schedule split --costs " + dir.write("u.csv", unequal));
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.out.find("split fractions: 0.750 0.250") != std::string::npos);
}

TEST_CASE("a solid the method cannot simulate: one line naming the line that chose it, exit code 2", "[fast]") {
  test::TempDir dir;
  const std::string box = "  - name: box\n    type: solid\n    box: {size: [0.2, 0.2, 0.2], resolution: [1, 1, 1]}\n";
  // neo-Hookean chosen on line 6, XPBD on line 8
  const std::string scene = dir.write("s.yaml", "objects:\n" + box +
                                                    "    material:\n      model: neo_hookean\n"
                                                    "solver:\n  method: xpbd\n");
  auto r = run_atssim(dir, "run " + scene + " -o " + dir.file("out.h5"));
  CHECK(r.code == 2);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.find(scene + ":6: solid 'box' is neo_hookean") != std::string::npos);
  CHECK(r.err.find("model to stvk") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("out.h5")));
  // the default model: the line that chose xpbd is to blame
  const std::string defaulted = dir.write("d.yaml", "objects:\n" + box + "solver:\n  method: xpbd\n");
  r = run_atssim(dir, "run " + defaulted + " -o " + dir.file("out.h5"));
  CHECK(r.code == 2);
  CHECK(r.err.find(defaulted + ":6: solid 'box' is neo_hookean (the default)") != std::string::npos);
  // the same scene runs with a method that simulates it
  r = run_atssim(dir, "run " + scene + " -o " + dir.file("out.h5") + " --set solver.method=vbd --frames 1 --quiet");
  INFO(r.err);
  CHECK(r.code == 0);
  // springs solids: tet-edge springs, which every method simulates (issue #13)
  r = run_atssim(
      dir, "run " + scene + " -o " + dir.file("out.h5") + " --set objects.0.material.model=springs --frames 1 --quiet");
  INFO(r.err);
  CHECK(r.code == 0);
}

TEST_CASE("a run finishes and marks its file complete while a reader holds the file open") {
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(24));
  const std::string out = dir.file("out.h5");
  Outcome r;
  std::thread run([&] { r = run_atssim(dir, "run " + scene + " -o " + out + " --frames 1500 --devices cpu/2:0"); });
  // A notebook watching the run: opened in SWMR mode while frames are written.
  hid_t reader = H5I_INVALID_HID;
  for (int i = 0; i < 400 && reader < 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
    try {
      if (io::read_summary(out).frames >= 2)
        reader = H5Fopen(out.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
    } catch (...) {
    }
  }
  bool complete_when_opened = true;
  if (reader >= 0) {
    int flag = 1;
    const hid_t attr = H5Aopen(reader, "complete", H5P_DEFAULT);
    H5Aread(attr, H5T_NATIVE_INT, &flag);
    H5Aclose(attr);
    complete_when_opened = flag != 0;
  }
  run.join();
  if (reader >= 0) H5Fclose(reader);
  REQUIRE(reader >= 0);
  REQUIRE_FALSE(complete_when_opened);  // the reader really was there before the end
  INFO(r.err);
  CHECK(r.code == 0);
  const auto s = io::read_summary(out);
  CHECK(s.complete);
  CHECK(s.frames == 1501);
}
