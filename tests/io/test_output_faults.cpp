// The output under faults (lib/io): one writer per path, a run that fails
// never replaces an earlier result, checkpoints that survive a torn write,
// and resuming a run into the same file.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/checkpoint.hpp"
#include "io/output_lock.hpp"
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

io::RunInfo run_info(const std::string& resolved = "a: 1\nframes: 3\n") {
  io::DeviceRecord d;
  d.name = "test device";
  return {"atssim run s.yaml", "a: 1\n", resolved, {d}, {}};
}

std::vector<std::byte> bytes_of(std::size_t n, int seed) {
  std::vector<std::byte> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = std::byte(static_cast<unsigned char>(seed * 31 + i * 7));
  return b;
}

std::vector<float> frame_of(std::size_t n, int f) { return std::vector<float>(n * 3, float(f)); }

}  // namespace

TEST_CASE("a second writer of one output path is refused until the first lets go") {
  test::TempDir dir;
  const std::string path = dir.file("out.h5");
  {
    io::OutputLock first(path);
    CHECK(std::filesystem::exists(path + ".lock"));
    try {
      io::OutputLock second(path);
      FAIL("the second lock was granted");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::input);
      CHECK(std::string(e.what()).find("another atssim run is writing") != std::string::npos);
    }
  }
  CHECK_FALSE(std::filesystem::exists(path + ".lock"));
  io::OutputLock again(path);  // free again
}

TEST_CASE("a partial file sits beside the output: out.h5 -> out.partial.h5") {
  CHECK(io::partial_path("dir/out.h5") == "dir/out.partial.h5");
  CHECK(io::partial_path("run") == "run.partial.h5");  // its sidecar must not be run.xdmf
}

TEST_CASE("a run at a path that holds a result writes beside it and replaces it only when it completes") {
  test::TempDir dir;
  const auto m = small_model();
  const std::size_t n = m.particles.size();
  const std::string path = dir.file("out.h5");
  {
    io::ResultWriter w(path, run_info(), m.objects);
    w.append_frame(0.0, frame_of(n, 7), 0.0);
    w.finish();
  }
  {
    io::ResultWriter w(path, run_info(), m.objects);
    CHECK(w.path() == dir.file("out.partial.h5"));
    w.append_frame(0.0, frame_of(n, 1), 0.0);
    w.append_frame(0.1, frame_of(n, 2), 0.0);
    w.fail("frame 2: interrupted");
  }
  auto s = io::read_summary(path);
  CHECK(s.complete);
  CHECK(s.frames == 1);
  CHECK(io::read_frame_positions(path, 0) == frame_of(n, 7));
  CHECK(io::read_summary(dir.file("out.partial.h5")).frames == 2);
  {
    io::ResultWriter w(path, run_info(), m.objects);
    w.append_frame(0.0, frame_of(n, 3), 0.0);
    w.append_frame(0.1, frame_of(n, 4), 0.0);
    w.finish();
    CHECK(w.path() == path);
  }
  s = io::read_summary(path);
  CHECK(s.complete);
  CHECK(s.frames == 2);
  CHECK(io::read_frame_positions(path, 1) == frame_of(n, 4));
  CHECK_FALSE(std::filesystem::exists(dir.file("out.partial.h5")));
  CHECK_FALSE(std::filesystem::exists(dir.file("out.partial.xdmf")));
}

namespace {
// Overwrites byte `col` of slot `row` of /checkpoint/state, as a write cut
// short would leave it; returns the bytes per slot.
hsize_t tear_state_byte(hid_t file, hsize_t row, hsize_t col) {
  const hid_t state = H5Dopen2(file, "checkpoint/state", H5P_DEFAULT);
  const hid_t space = H5Dget_space(state);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  const hsize_t start[2] = {row, col}, count[2] = {1, 1};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
  const hid_t mem = H5Screate_simple(2, count, nullptr);
  const unsigned char torn = 0xEE;
  REQUIRE(H5Dwrite(state, H5T_NATIVE_UCHAR, mem, space, H5P_DEFAULT, &torn) >= 0);
  H5Sclose(mem);
  H5Sclose(space);
  H5Dclose(state);
  return dims[1];
}
}  // namespace

TEST_CASE("a checkpoint keeps the carried bytes after the velocities, and a torn carried byte spoils its slot") {
  test::TempDir dir;
  const std::string path = dir.file("c.h5");
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(file >= 0);
  {
    auto slots = io::CheckpointSlots::create(file, 16, 8, 12);
    CHECK(slots.carried_bytes() == 12);
    for (int k = 1; k <= 2; ++k)
      slots.write({k, k + 1, 0, 0, 0, bytes_of(16, k), bytes_of(8, -k), bytes_of(12, 50 + k)});
    CHECK_THROWS_AS(slots.write({3, 4, 0, 0, 0, bytes_of(16, 3), bytes_of(8, -3), {}}), std::logic_error);
    // Frame 2 went to slot 1: tear its last carried byte (column 16 + 8 + 11 of 36).
    CHECK(tear_state_byte(file, 1, 35) == 36);
  }
  auto reopened = io::CheckpointSlots::open(file);
  REQUIRE(reopened);
  CHECK(reopened->carried_bytes() == 12);
  const auto c = reopened->take_newest(100);
  REQUIRE(c);
  CHECK(c->frame == 1);
  CHECK(c->positions == bytes_of(16, 1));
  CHECK(c->velocities == bytes_of(8, -1));
  CHECK(c->carried == bytes_of(12, 51));
  H5Fclose(file);
}

TEST_CASE("a checkpoint slot whose bytes were torn is skipped for the other slot") {
  test::TempDir dir;
  const std::string path = dir.file("c.h5");
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(file >= 0);
  {
    auto slots = io::CheckpointSlots::create(file, 16, 8);
    for (int k = 1; k <= 3; ++k) slots.write({k, k + 1, 0, 0, 0, bytes_of(16, k), bytes_of(8, -k), {}});
    // Frame 3 went to slot 0 (1 -> 0, 2 -> 1, 3 -> 0): tear its state bytes.
    tear_state_byte(file, 0, 5);
    // as a file written before atssim kept carried bytes
    REQUIRE(H5Adelete_by_name(file, "checkpoint", "carried_bytes", H5P_DEFAULT) >= 0);
  }
  auto reopened = io::CheckpointSlots::open(file);
  REQUIRE(reopened);
  CHECK(reopened->carried_bytes() == 0);
  const auto c = reopened->take_newest(100);
  REQUIRE(c);
  CHECK(c->frame == 2);
  CHECK(c->frames_written == 3);
  CHECK(c->positions == bytes_of(16, 2));
  CHECK(c->velocities == bytes_of(8, -2));
  CHECK(c->carried.empty());              // none kept
  CHECK_FALSE(reopened->take_newest(2));  // frame 2 needs 3 frames in the file
  H5Fclose(file);
}

namespace {

// A run of `frames` frames, each with its checkpoint (state bytes_of(f) and
// bytes_of(100 + f)), that failed before its end.
void write_stopped_run(const std::string& path, const model::Model& m, int frames) {
  const std::size_t n = m.particles.size();
  io::ResultWriter w(path, run_info(), m.objects);
  for (int f = 0; f < frames; ++f) {
    w.set_checkpoint(f, bytes_of(n * 16, f), bytes_of(n * 16, 100 + f));
    w.append_frame(f * 0.1, frame_of(n, f), 1.0);
  }
  w.fail("interrupted");
}

}  // namespace

TEST_CASE("a stopped run resumes from its last checkpoint into the same file") {
  test::TempDir dir;
  const auto m = small_model();
  const std::size_t n = m.particles.size();
  const std::string path = dir.file("run.h5");
  write_stopped_run(path, m, 4);
  io::Checkpoint c;
  {
    // Frames may change on resume; the rest of the resolved scene may not.
    io::ResultWriter w(path, run_info("a: 1\nframes: 9\n"), m.objects, &c);
    CHECK(c.frame == 3);
    CHECK(c.frames_written == 4);
    CHECK(c.positions == bytes_of(n * 16, 3));
    CHECK(c.velocities == bytes_of(n * 16, 103));
    CHECK(w.frames_written() == 4);
    w.set_checkpoint(4, bytes_of(n * 16, 4), bytes_of(n * 16, 104));
    w.append_frame(0.4, frame_of(n, 4), 1.0);
    w.finish();
  }
  const auto s = io::read_summary(path);
  CHECK(s.complete);
  CHECK(s.frames == 5);
  CHECK(s.time.size() == 5);
  for (int f = 0; f < 5; ++f) CHECK(io::read_frame_positions(path, f) == frame_of(n, f));
  std::ifstream x(dir.file("run.xdmf"));
  std::stringstream text;
  text << x.rdbuf();
  CHECK(text.str().find("Name=\"frame4\"") != std::string::npos);
  CHECK(text.str().find("Name=\"frame5\"") == std::string::npos);
}

TEST_CASE("a run killed inside a frame's flush resumes from the last frame /frames/flushed counts") {
  // The kill left frame 3's rows and its checkpoint in the file, but not the
  // record that they were flushed in full: HDF5 writes the parts of a flush
  // in no set order, so the row may be missing while the checkpoint is whole.
  test::TempDir dir;
  const auto m = small_model();
  const std::size_t n = m.particles.size();
  const std::string path = dir.file("run.h5");
  write_stopped_run(path, m, 4);
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    REQUIRE(file >= 0);
    const hid_t set = H5Dopen2(file, "frames/flushed", H5P_DEFAULT);
    REQUIRE(set >= 0);
    const long long three[1] = {3};
    REQUIRE(H5Dwrite(set, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, three) >= 0);
    H5Dclose(set);
    H5Fclose(file);
  }
  io::Checkpoint c;
  {
    io::ResultWriter w(path, run_info(), m.objects, &c);
    CHECK(c.frame == 2);
    CHECK(c.frames_written == 3);
    CHECK(c.positions == bytes_of(n * 16, 2));
    CHECK(w.frames_written() == 3);
    w.set_checkpoint(3, bytes_of(n * 16, 3), bytes_of(n * 16, 103));
    w.append_frame(0.3, frame_of(n, 33), 1.0);
    w.finish();
  }
  const auto s = io::read_summary(path);
  CHECK(s.frames == 4);
  CHECK(io::read_frame_positions(path, 3) == frame_of(n, 33));  // written again, not kept
}

TEST_CASE("a resumed run keeps the contact records of its kept frames and cuts the rest") {
  test::TempDir dir;
  const auto m = small_model();
  const std::size_t n = m.particles.size();
  const std::string path = dir.file("run.h5");
  const auto contact = [](int f) {
    io::ContactFrame c;
    c.active = f;
    c.min_distance = 0.5 * f;
    c.max_penetration = 0.25 * f;
    c.surface_pairs = 10 + f;
    c.surface_max_penetration = 0.001 * f;
    c.surface_crossings = f % 2;
    return c;
  };
  {
    io::ResultWriter w(path, run_info(), m.objects);
    for (int f = 0; f < 4; ++f) {
      if (f < 3) w.set_checkpoint(f, bytes_of(n * 16, f), bytes_of(n * 16, 100 + f));  // frame 3: no checkpoint
      w.append_frame(f * 0.1, frame_of(n, f), 1.0, 0.0, contact(f));
    }
    w.fail("interrupted");
  }
  io::Checkpoint c;
  {
    io::ResultWriter w(path, run_info(), m.objects, &c);
    REQUIRE(c.frame == 2);
    REQUIRE(w.resumed_contact().size() == 3);
    for (int f = 0; f < 3; ++f) {
      const io::ContactFrame& r = w.resumed_contact()[f];
      CHECK(r.active == f);
      CHECK(r.min_distance == 0.5 * f);
      CHECK(r.max_penetration == 0.25 * f);
      CHECK(r.surface_pairs == 10 + f);
      CHECK(r.surface_max_penetration == 0.001 * f);
      CHECK(r.surface_crossings == f % 2);
    }
    w.set_checkpoint(3, bytes_of(n * 16, 3), bytes_of(n * 16, 103));
    w.append_frame(0.3, frame_of(n, 3), 1.0, 0.0, contact(7));
    w.finish();
  }
  const std::vector<double> pairs = io::read_series(path, "/contact/surface_pairs");
  CHECK(pairs == std::vector<double>{10, 11, 12, 17});
  CHECK(io::read_series(path, "/contact/surface_crossings") == std::vector<double>{0, 1, 0, 1});
  CHECK(io::read_series(path, "/contact/surface_max_penetration").size() == 4);
}

TEST_CASE("resuming is refused for a complete run and for a different scene") {
  test::TempDir dir;
  const auto m = small_model();
  const std::size_t n = m.particles.size();
  const std::string path = dir.file("run.h5");
  {
    io::ResultWriter w(path, run_info(), m.objects);
    w.set_checkpoint(0, bytes_of(16, 0), {});
    w.append_frame(0.0, frame_of(n, 0), 0.0);
    w.fail("interrupted");
  }
  io::Checkpoint c;
  CHECK_THROWS_WITH(io::ResultWriter(path, run_info("a: 2\nframes: 3\n"), m.objects, &c),
                    Catch::Contains("different scene"));
  {
    io::ResultWriter w(path, run_info(), m.objects, &c);
    w.finish();
  }
  CHECK_THROWS_WITH(io::ResultWriter(path, run_info(), m.objects, &c), Catch::Contains("complete run"));
  CHECK_THROWS_WITH(io::ResultWriter(dir.file("none.h5"), run_info(), m.objects, &c), Catch::Contains("no '"));
}
