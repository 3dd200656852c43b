#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include "scene/mesh_loader.hpp"
#include "scene/ply_header.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

// A binary little-endian PLY of one triangle: 3 vertices of 3 floats (36
// bytes), one face of a uchar count and 3 ints (13 bytes): 49 bytes after
// the header, counted by hand from the PLY format.
std::string one_triangle_ply(const std::string& face_count, int payload_bytes = 49) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\ncomment one triangle\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face " +
      face_count + "\nproperty list uchar int vertex_indices\nend_header\n";
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string body(reinterpret_cast<const char*>(xyz), sizeof xyz);
  body += '\3';
  const int ids[3] = {0, 1, 2};
  body.append(reinterpret_cast<const char*>(ids), sizeof ids);
  REQUIRE(body.size() == 49);
  return ply + body.substr(0, payload_bytes);
}

}  // namespace

TEST_CASE("a PLY header's counts give the least bytes each element takes") {
  test::TempDir dir;
  const auto h = scene::read_ply_header(dir.write("t.ply", one_triangle_ply("1")));
  REQUIRE(h.elements.size() == 2);
  CHECK(h.binary);
  CHECK(h.elements[0].name == "vertex");
  CHECK(h.elements[0].count == 3);
  CHECK(h.elements[0].min_bytes == 12);
  CHECK(h.elements[0].line == 4);
  CHECK(h.elements[1].name == "face");
  CHECK(h.elements[1].min_bytes == 1);  // a list may hold no index: its count alone
  CHECK(h.elements[1].line == 8);

  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\nend_header\n";
  const auto a = scene::read_ply_header(dir.write("a.ply", ascii + "0 0\n1 1\n"));
  REQUIRE(a.elements.size() == 1);
  CHECK_FALSE(a.binary);
  CHECK(a.elements[0].min_bytes == 4);  // a digit and a separator per value
  CHECK(a.header_bytes == ascii.size());
  CHECK(a.end_line == 6);
  CHECK(scene::read_ply_header(dir.write("x.obj", "v 0 0 0\n")).elements.empty());
}

TEST_CASE("a PLY whose header declares more faces than the file holds is refused before it is read") {
  test::TempDir dir;
  // The file as it should be loads; the same bytes declaring 2e9 faces (32
  // GB of assimp's faces) are one input error naming the element and line.
  CHECK(scene::load_triangle_mesh(dir.write("ok.ply", one_triangle_ply("1")), "scene.yaml:8").triangles.size() == 1);
  const std::string huge = dir.write("huge.ply", one_triangle_ply("2000000000"));
  CHECK_NOTHROW(scene::check_ply_counts(dir.write("ok2.ply", one_triangle_ply("1")), "scene.yaml:8"));
  try {
    scene::load_triangle_mesh(huge, "scene.yaml:8");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::input);
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains("scene.yaml:8: cannot read mesh"));
    CHECK_THAT(what, Catch::Contains("(line 8) declares 2000000000 'face' elements, which the 49 bytes"));
  }
  // Truncated after the vertices: the face's count byte is missing.
  CHECK_THROWS_AS(scene::check_ply_counts(dir.write("short.ply", one_triangle_ply("1", 36)), "scene.yaml:8"), Error);
}
