#include "scene/tetgen_reader.hpp"

#include <fmt/format.h>

#include "scene/text_lines.hpp"

namespace atssim::scene {

namespace {

constexpr long long kMaxCount = 100'000'000;  // beyond this a header is surely corrupt

// Returns the first point number (0 or 1): TetGen numbers from whatever the
// first point says and every index in the .ele follows it.
long long read_nodes(const std::string& path, TetMesh& mesh) {
  TextLines in(path, true);
  constexpr std::string_view kHeader = "<#points> <dimension 3> <#attributes> <boundary markers 0|1>";
  in.expect_next("the header line");
  in.require(1, kHeader);
  const long long count = in.integer(0, "the number of points");
  const long long dim = in.size() > 1 ? in.integer(1, "the dimension") : 3;
  const long long attributes = in.size() > 2 ? in.integer(2, "the number of attributes") : 0;
  const long long markers = in.size() > 3 ? in.integer(3, "the boundary-marker flag") : 0;
  if (count <= 0 || count > kMaxCount) {
    in.fail(fmt::format("the header gives {} points", count), "a tetrahedral mesh needs at least 4 points");
  }
  if (dim != 3) in.fail(fmt::format("the dimension is {}", dim), "give a 3D mesh (dimension 3)");
  if (attributes < 0 || markers < 0 || markers > 1) {
    in.fail("the attribute count or boundary-marker flag is invalid",
            "the header should read '" + std::string(kHeader) + "'");
  }
  const std::size_t per_line = 4 + static_cast<std::size_t>(attributes + markers);
  const std::string layout = fmt::format("<point #> <x> <y> <z>{}{}", attributes > 0 ? " <attributes…>" : "",
                                         markers > 0 ? " <boundary marker>" : "");
  long long base = 0;
  mesh.vertices.reserve(static_cast<std::size_t>(count));
  for (long long i = 0; i < count; ++i) {
    in.expect_next(fmt::format("point {} of {}", i + 1, count));
    in.require(per_line, layout);
    const long long number = in.integer(0, "the point number");
    if (i == 0) {
      if (number != 0 && number != 1) {
        in.fail(fmt::format("the first point is numbered {}", number), "number points from 0 or from 1");
      }
      base = number;
    } else if (number != base + i) {
      in.fail(fmt::format("point {} follows point {}", number, base + i - 1),
              fmt::format("number the points consecutively (expected {})", base + i));
    }
    const std::string label = fmt::format("of point {}", number);
    mesh.vertices.push_back({in.number(1, "x " + label), in.number(2, "y " + label), in.number(3, "z " + label)});
  }
  return base;
}

void read_elements(const std::string& path, long long base, TetMesh& mesh) {
  TextLines in(path, true);
  constexpr std::string_view kHeader = "<#tetrahedra> <nodes per tetrahedron 4|10> <#attributes>";
  in.expect_next("the header line");
  in.require(1, kHeader);
  const long long count = in.integer(0, "the number of tetrahedra");
  const long long nodes = in.size() > 1 ? in.integer(1, "the number of nodes per tetrahedron") : 4;
  const long long attributes = in.size() > 2 ? in.integer(2, "the number of attributes") : 0;
  if (count <= 0 || count > kMaxCount) {
    in.fail(fmt::format("the header gives {} tetrahedra", count), "give at least one tetrahedron");
  }
  if (nodes != 4 && nodes != 10) {
    in.fail(fmt::format("tetrahedra have {} nodes", nodes), "use 4-node (or 10-node) tetrahedra");
  }
  if (attributes < 0) in.fail("the attribute count is negative", fmt::format("the header should read '{}'", kHeader));
  const std::size_t per_line = 1 + static_cast<std::size_t>(nodes + attributes);
  const std::string layout =
      fmt::format("<tetrahedron #> <{} point numbers>{}", nodes, attributes > 0 ? " <attributes…>" : "");
  const long long points = static_cast<long long>(mesh.vertices.size());
  for (long long i = 0; i < count; ++i) {
    in.expect_next(fmt::format("tetrahedron {} of {}", i + 1, count));
    in.require(per_line, layout);
    const long long number = in.integer(0, "the tetrahedron number");
    std::array<int, 4> tet{};
    for (int k = 0; k < 4; ++k) {
      const long long p = in.integer(1 + k, fmt::format("corner {} of tetrahedron {}", k + 1, number));
      if (p < base || p >= base + points) {
        in.fail(fmt::format("tetrahedron {} names point {}, which the .node file does not define", number, p),
                fmt::format("use point numbers from {} to {} (as in the .node file)", base, base + points - 1));
      }
      tet[k] = static_cast<int>(p - base);
    }
    mesh.tetrahedra.push_back(tet);
    mesh.element_line.push_back(in.line());
    mesh.element_label.push_back(number);
  }
}

}  // namespace

TetMesh read_tetgen(const std::string& node_path, const std::string& ele_path) {
  TetMesh mesh;
  mesh.file = ele_path;
  const long long base = read_nodes(node_path, mesh);
  read_elements(ele_path, base, mesh);
  return mesh;
}

}  // namespace atssim::scene
