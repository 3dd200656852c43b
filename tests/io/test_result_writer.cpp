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

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

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

TEST_CASE("the XDMF sidecar lists every written frame as a grid of the frame's view and the objects' cells") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("run.h5");
  std::vector<float> xyz(m.particles.size() * 3, 0.0f);
  {
    io::ResultWriter w(path, run_info(), m.objects);
    for (int f = 0; f < 3; ++f) w.append_frame(f / 60.0, xyz, 1.0);
    w.finish();
  }
  const std::string x = slurp(dir.file("run.xdmf"));
  CHECK(x.find("run.h5:/xdmf/frames/2</DataItem>") != std::string::npos);
  CHECK(x.find("run.h5:/xdmf/cells") != std::string::npos);
  CHECK(x.find("TopologyType=\"Mixed\" NumberOfElements=\"32\"") != std::string::npos);  // 4 × 4 quads × 2
  CHECK(x.find("Name=\"frame2\"") != std::string::npos);
  CHECK(x.find("Name=\"frame3\"") == std::string::npos);
  CHECK(x.find("HyperSlab") == std::string::npos);  // ParaView 5.11 skips that item
}

TEST_CASE("each frame's XDMF view reads as that frame's positions") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("run.h5");
  const std::size_t n = m.particles.size();
  {
    io::ResultWriter w(path, run_info(), m.objects);
    for (int f = 0; f < 3; ++f) {
      std::vector<float> xyz(n * 3);
      for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] = float(f * 1000 + i);
      w.append_frame(f / 60.0, xyz, 1.0);
    }
    w.finish();
  }
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  for (int f = 0; f < 3; ++f) {
    const std::string name = "/xdmf/frames/" + std::to_string(f);
    const hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
    REQUIRE(set >= 0);
    std::vector<float> view(n * 3, -1.0f);
    REQUIRE(H5Dread(set, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, view.data()) >= 0);
    H5Dclose(set);
    CHECK(view == io::read_frame_positions(path, f));
    CHECK(view[1] == float(f * 1000 + 1));
  }
  H5Fclose(file);
}

TEST_CASE("while the run writes, the XDMF sidecar's geometry is an XDMF 3 hyperslab, and views come at the end") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("run.h5");
  std::vector<float> xyz(m.particles.size() * 3, 0.0f);
  io::ResultWriter w(path, run_info(), m.objects);
  w.append_frame(0.0, xyz, 1.0);
  w.append_frame(1 / 60.0, xyz, 1.0);  // 2 frames: the sidecar is rewritten
  const std::string during = slurp(dir.file("run.xdmf"));
  CHECK(during.find("run.h5:/frames/positions|1 0 0:1 1 1:1 25 3:2 25 3</DataItem>") != std::string::npos);
  CHECK(during.find("/xdmf/frames/") == std::string::npos);
  w.finish();
  const std::string after = slurp(dir.file("run.xdmf"));
  CHECK(after.find("run.h5:/xdmf/frames/1</DataItem>") != std::string::npos);
  CHECK(after.find("/frames/positions|") == std::string::npos);
}

TEST_CASE("reading something that is not an atssim file is an input error") {
  test::TempDir dir;
  CHECK_THROWS_AS(io::read_summary(dir.file("missing.h5")), Error);
  CHECK_THROWS_AS(io::read_summary(dir.write("junk.h5", "not hdf5")), Error);
}

namespace {

// /frames/flushed of `path`, read by a second handle as a reader would.
long long flushed_frames(const std::string& path) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t d = H5Dopen2(f, "frames/flushed", H5P_DEFAULT);
  REQUIRE(d >= 0);
  long long n = -1;
  CHECK(H5Dread(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &n) >= 0);
  H5Dclose(d);
  H5Fclose(f);
  return n;
}

}  // namespace

TEST_CASE("/frames/flushed counts the frames on disk in full after every append, for a reader that opens the file") {
  test::TempDir dir;
  const auto m = small_model();
  const std::string path = dir.file("out.h5");
  const std::vector<float> xyz(m.particles.size() * 3, 0.5f);
  io::ResultWriter w(path, run_info(), m.objects);
  CHECK(flushed_frames(path) == 0);
  for (int f = 1; f <= 3; ++f) {
    w.append_frame(0.1 * f, xyz, 1.0);
    CHECK(flushed_frames(path) == f);  // while the writer still holds the file
  }
  w.finish();
  CHECK(flushed_frames(path) == 3);
}
