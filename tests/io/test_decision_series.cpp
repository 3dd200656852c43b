#include <catch2/catch.hpp>

#include <cmath>

#include "io/result_reader.hpp"
#include "io/result_writer.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

model::Model small_model() {
  return model::build_model(scene::parse_scene(test::hanging_cloth_yaml(5), "s.yaml", "."));
}

io::RunInfo run_info() { return {"atssim run s.yaml --tolerance 0.01", "a: 1\n", "a: 1\nframes: 3\n", {}, {}}; }

std::vector<std::byte> state_bytes(std::size_t n, int seed) {
  std::vector<std::byte> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::byte>((i * 7 + seed) & 0xff);
  return b;
}

io::DecisionRecord row(int frame, const std::string& method, int iterations, double y) {
  io::DecisionRecord r;
  r.frame = frame;
  r.method = method;
  r.iterations = iterations;
  r.schedule = "split";
  r.y = y;
  r.y_floor = 1e-6;
  r.predicted_ms = 2.5 * iterations;
  r.check_ms = 40.0;
  r.changed = 1;
  r.reason = "probe: the cheapest choice that meets the tolerance";
  return r;
}

}  // namespace

TEST_CASE("/decisions rows read back as written, the measured time filled in when the next row comes") {
  test::TempDir dir;
  const auto m = small_model();
  const std::size_t n = m.particles.size();
  const std::string path = dir.file("run.h5");
  {
    io::ResultWriter w(path, run_info(), m.objects);
    w.append_decision(row(0, "vbd", 16, 4e-3));
    w.append_frame(0.0, std::vector<float>(n * 3, 0.0f), 0.0);
    w.append_frame(0.1, std::vector<float>(n * 3, 1.0f), 3.0);
    w.set_decision_measured(3.5);
    w.append_decision(row(1, "jpgd", 23, 8e-3));
    w.append_frame(0.2, std::vector<float>(n * 3, 2.0f), 3.0);
    w.finish();
  }
  const std::vector<io::DecisionRecord> d = io::read_decisions(path);
  REQUIRE(d.size() == 2);
  CHECK(d[0].frame == 0);
  CHECK(d[0].method == "vbd");
  CHECK(d[0].iterations == 16);
  CHECK(d[0].schedule == "split");
  CHECK(d[0].y == 4e-3);
  CHECK(d[0].predicted_ms == 40.0);
  CHECK(d[0].measured_ms == 3.5);
  CHECK(d[0].reason == "probe: the cheapest choice that meets the tolerance");
  CHECK(d[1].method == "jpgd");
  CHECK(std::isnan(d[1].measured_ms));  // never set: its frames' time was not recorded
  CHECK(std::isnan(d[1].previous_y));
  CHECK(d[1].check_ms == 40.0);
}

TEST_CASE("a resumed run keeps the /decisions rows up to its checkpoint and appends after them") {
  test::TempDir dir;
  const auto m = small_model();
  const std::size_t n = m.particles.size();
  const std::string path = dir.file("run.h5");
  {
    io::ResultWriter w(path, run_info(), m.objects);
    w.append_decision(row(0, "vbd", 16, 4e-3));
    for (int f = 0; f < 3; ++f) {
      if (f == 2) w.append_decision(row(2, "vbd", 23, 9e-3));
      w.set_checkpoint(f, state_bytes(n * 16, f), state_bytes(n * 16, 100 + f));
      w.append_frame(0.1 * f, std::vector<float>(n * 3, float(f)), 1.0);
    }
    // Made after the last flush, in the frame the run was killed in.
    w.append_decision(row(3, "jpgd", 32, 5e-3));
    w.fail("interrupted");
  }
  io::Checkpoint c;
  {
    io::ResultWriter w(path, run_info(), m.objects, &c);
    REQUIRE(c.frame == 2);
    REQUIRE(w.decisions().size() == 2);
    CHECK(w.decisions()[1].iterations == 23);
    w.append_decision(row(3, "xpbd", 64, 6e-3));
    w.set_checkpoint(3, state_bytes(n * 16, 3), state_bytes(n * 16, 103));
    w.append_frame(0.3, std::vector<float>(n * 3, 3.0f), 1.0);
    w.finish();
  }
  const std::vector<io::DecisionRecord> d = io::read_decisions(path);
  REQUIRE(d.size() == 3);
  CHECK(d[2].method == "xpbd");
  CHECK(d[2].frame == 3);
}

TEST_CASE("a file of a run without a tolerance has no /decisions") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("run.h5");
  {
    io::ResultWriter w(path, run_info(), m.objects);
    w.append_frame(0.0, std::vector<float>(m.particles.size() * 3, 0.0f), 0.0);
    w.finish();
  }
  CHECK(io::read_decisions(path).empty());
}
