#include <catch2/catch.hpp>

#include <cstring>
#include <vector>

#include <hdf5.h>

#include "io/result_reader.hpp"
#include "io/result_writer.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

// FNV-1a byte by byte (Fowler, Noll and Vo's published definition), the
// hash of every checkpoint atssim wrote before its carried state grew to
// tens of megabytes; written out here apart from lib/io.
std::uint64_t fnv1a_bytes(std::uint64_t h, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

std::vector<std::byte> pattern(std::size_t size, int seed) {
  std::vector<std::byte> v(size);
  for (std::size_t i = 0; i < size; ++i) v[i] = std::byte((i * 37 + std::size_t(seed) * 101 + 7) & 0xff);
  return v;
}

// Row `row` of /checkpoint/index: frame, frames_written, three row counts, hash.
void set_index_hash(const std::string& path, int row, std::uint64_t hash) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t set = H5Dopen2(file, "/checkpoint/index", H5P_DEFAULT);
  long long rows[12] = {};
  REQUIRE(H5Dread(set, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) >= 0);
  std::memcpy(&rows[6 * row + 5], &hash, sizeof hash);
  REQUIRE(H5Dwrite(set, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) >= 0);
  H5Dclose(set);
  H5Fclose(file);
}

int row_of_frame(const std::string& path, long long frame) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t set = H5Dopen2(file, "/checkpoint/index", H5P_DEFAULT);
  long long rows[12] = {};
  H5Dread(set, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows);
  H5Dclose(set);
  H5Fclose(file);
  return rows[0] == frame ? 0 : rows[6] == frame ? 1 : -1;
}

}  // namespace

TEST_CASE("a checkpoint reads back its three parts, and one hashed byte by byte (an older atssim's) still resumes") {
  test::TempDir dir;
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(5), "s.yaml", "."));
  const std::string path = dir.file("out.h5");
  const std::size_t n = m.particles.size();
  // A carried part whose size is no multiple of 8: the hash's tail.
  const std::vector<std::byte> x1 = pattern(16 * n, 1), v1 = pattern(16 * n, 2), c1 = pattern(1237, 3);
  const std::vector<std::byte> x2 = pattern(16 * n, 4), v2 = pattern(16 * n, 5), c2 = pattern(1237, 6);
  std::vector<float> xyz(3 * n, 0.0f);
  {
    io::ResultWriter w(path, {"atssim run s.yaml", "a: 1\n", "a: 1\n", {}, {}}, m.objects);
    w.set_checkpoint(1, x1, v1, c1);
    w.append_frame(0.1, xyz, 1.0);
    w.set_checkpoint(2, x2, v2, c2);
    w.append_frame(0.2, xyz, 1.0);
    w.finish();
  }
  const io::Checkpoint newest = io::read_checkpoint(path);
  CHECK(newest.frame == 2);
  CHECK(newest.positions == x2);
  CHECK(newest.velocities == v2);
  CHECK(newest.carried == c2);

  const int row = row_of_frame(path, 2);
  REQUIRE(row >= 0);
  std::uint64_t h = 14695981039346656037ull;
  const long long fields[5] = {newest.frame, newest.frames_written, newest.schedule_rows, newest.wait_rows,
                               newest.makespan_rows};
  h = fnv1a_bytes(h, fields, sizeof fields);
  h = fnv1a_bytes(h, x2.data(), x2.size());
  h = fnv1a_bytes(h, v2.data(), v2.size());
  h = fnv1a_bytes(h, c2.data(), c2.size());
  SECTION("the byte-wise hash of an older file is accepted") {
    set_index_hash(path, row, h);
    const io::Checkpoint old = io::read_checkpoint(path);
    CHECK(old.frame == 2);
    CHECK(old.carried == c2);
  }
  SECTION("a hash that matches neither leaves the slot out: the older one is read") {
    set_index_hash(path, row, h ^ 1u);
    const io::Checkpoint other = io::read_checkpoint(path);
    CHECK(other.frame == 1);
    CHECK(other.positions == x1);
    CHECK(other.carried == c1);
  }
}
