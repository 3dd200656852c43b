// --resume (README, docs/output-format.md): a stopped run continued from its
// checkpoint writes the positions of an uninterrupted run on one device, bit
// for bit, under every method. The stop comes from the progress callback
// (app::request_stop, what Ctrl-C calls), so it falls after a known frame;
// tests/faults/test_faults.py kills the real binary at a random one.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "solver/method_registry.hpp"
#include "support/methods.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

constexpr int kFrames = 6;
constexpr int kStopAfter = 3;

}  // namespace

TEST_CASE("a run stopped after frame 3 and resumed writes the uninterrupted run's positions bit for bit, every method",
          "[resume]") {
  const std::string method = GENERATE(from_range(test::method_names()));
  const solver::MethodDescription& description = solver::method(method);
  INFO(method);
  test::TempDir dir;
  // A cloth and a soft box on the ground; with surface contact where the
  // method has contact (explicit has none).
  const std::string scene = dir.write("scene.yaml", test::cloth_and_box_yaml(method, 8));
  const auto options = [&](const std::string& out) {
    app::RunOptions o;
    o.scene_path = scene;
    o.overrides = {"output.path=" + dir.file(out), "devices=cpu", "simulation.frames=" + std::to_string(kFrames)};
    if (description.colliders) o.overrides.push_back("contact.self=true");
    if (method == "explicit") o.overrides.push_back("simulation.substeps=64");  // its stable step
    return o;
  };
  app::run_simulation(options("full.h5"));

  app::RunOptions stopped = options("resumed.h5");
  try {
    app::run_simulation(stopped, [](const app::RunProgress& p) {
      if (p.frame == kStopAfter) app::request_stop();
    });
    FAIL("the run did not stop");
  } catch (const Error& e) {
    INFO(e.what());
    CHECK(e.exit_code() == 1);
    CHECK(std::string(e.what()).find("interrupted") != std::string::npos);
  }
  const io::ResultSummary kept = io::read_summary(dir.file("resumed.h5"));
  CHECK_FALSE(kept.complete);
  REQUIRE(kept.frames == kStopAfter + 1);  // the initial state and the frames before the stop

  stopped.resume = true;
  app::run_simulation(stopped);
  const io::ResultSummary resumed = io::read_summary(dir.file("resumed.h5"));
  CHECK(resumed.complete);
  REQUIRE(resumed.frames == kFrames + 1);
  for (std::size_t f = 0; f <= kFrames; ++f) {
    INFO("frame " << f);
    CHECK(io::read_frame_positions(dir.file("resumed.h5"), f) == io::read_frame_positions(dir.file("full.h5"), f));
  }
  // and the frames compared are not all the start: the bodies moved.
  CHECK(io::read_frame_positions(dir.file("full.h5"), kFrames) != io::read_frame_positions(dir.file("full.h5"), 0));
}
