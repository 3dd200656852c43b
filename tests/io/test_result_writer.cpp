#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "io/result_reader.hpp"
#include "io/result_writer.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

model::Model small_model() {
  return model::build_model(scene::parse_scene(test::hanging_cloth_yaml(5), "s.yaml", "."));
}

io::RunInfo run_info() {
  io::DeviceRecord d;
  d.name = "test device";
  d.type = "cpu";
  d.compute_units = 1;
  return {"atssim run s.yaml", "a: 1\n", "a: 1\nb: 2\n", {d}, {}};
}

}  // namespace

TEST_CASE("positions written to HDF5 and read back are equal") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("out.h5");
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  std::vector<std::vector<float>> frames(4, std::vector<float>(m.particles.size() * 3));
  for (auto& f : frames) {
    for (float& v : f) v = u(rng);
  }
  {
    io::ResultWriter w(path, run_info(), m.objects);
    for (std::size_t f = 0; f < frames.size(); ++f) w.append_frame(0.1 * f, frames[f], 1.5);
    w.finish();
  }
  const auto s = io::read_summary(path);
  CHECK(s.format == "atssim");
  CHECK(s.format_version == 1);
  CHECK(s.complete);
  CHECK(s.frames == 4);
  CHECK(s.particles == m.particles.size());
  CHECK(s.devices == std::vector<std::string>{"test device"});
  CHECK(s.objects == std::vector<std::string>{"cloth"});
  CHECK(s.time[3] == Approx(0.3));
  for (std::size_t f = 0; f < frames.size(); ++f) CHECK(io::read_frame_positions(path, f) == frames[f]);
}

TEST_CASE("a failed run keeps its frames and records the error") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("out.h5");
  std::vector<float> xyz(m.particles.size() * 3, 1.0f);
  {
    io::ResultWriter w(path, run_info(), m.objects);
    w.append_frame(0.0, xyz, 0.0);
    w.append_frame(0.1, xyz, 1.0);
    w.fail("frame 2: the simulation blew up");
  }
  const auto s = io::read_summary(path);
  CHECK_FALSE(s.complete);
  CHECK(s.error == "frame 2: the simulation blew up");
  CHECK(s.frames == 2);
}

TEST_CASE("the XDMF sidecar points ParaView at every frame of the HDF5 file") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("run.h5");
  std::vector<float> xyz(m.particles.size() * 3, 0.0f);
  {
    io::ResultWriter w(path, run_info(), m.objects);
    for (int f = 0; f < 3; ++f) w.append_frame(f / 60.0, xyz, 1.0);
    w.finish();
  }
  std::ifstream in(dir.file("run.xdmf"));
  REQUIRE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  const std::string x = text.str();
  CHECK(x.find("run.h5:/frames/positions") != std::string::npos);
  CHECK(x.find("run.h5:/mesh/cloth/triangles") != std::string::npos);
  CHECK(x.find("Name=\"frame2\"") != std::string::npos);
  CHECK(x.find("Name=\"frame3\"") == std::string::npos);
}

TEST_CASE("reading something that is not an atssim file is an input error") {
  test::TempDir dir;
  CHECK_THROWS_AS(io::read_summary(dir.file("missing.h5")), Error);
  CHECK_THROWS_AS(io::read_summary(dir.write("junk.h5", "not hdf5")), Error);
}
