#include "scene/gmsh_reader.hpp"

#include <unordered_map>

#include <fmt/format.h>

#include "scene/text_lines.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

constexpr int kTet4 = 4;    // Gmsh element type of the 4-node tetrahedron
constexpr int kTet10 = 11;  // second-order tetrahedron: named in the error, not read
constexpr long long kMaxCount = 100'000'000;
constexpr std::string_view kExportAscii =
    "export ASCII 4.1 or 2.2 instead: in Gmsh File > Export > 'Mesh - Gmsh MSH' with the ASCII format, or "
    "'gmsh model.geo -3 -format msh41 -o model.msh' (without -bin)";

struct GmshState {
  TetMesh mesh;
  std::unordered_map<long long, int> node_index;  // tag -> vertex
  bool has_nodes = false;
  bool has_second_order = false;
};

long long count_in(const TextLines& in, std::size_t i, std::string_view what) {
  const long long n = in.integer(i, what);
  if (n < 0 || n > kMaxCount) in.fail(fmt::format("{} is {}", what, n), "the header is corrupt; export the mesh again");
  return n;
}

void add_node(TextLines& in, GmshState& st, long long tag, std::size_t first_coordinate) {
  const std::string label = fmt::format("of node {}", tag);
  const std::array<double, 3> x{in.number(first_coordinate, "x " + label),
                                in.number(first_coordinate + 1, "y " + label),
                                in.number(first_coordinate + 2, "z " + label)};
  const auto [it, added] = st.node_index.emplace(tag, static_cast<int>(st.mesh.vertices.size()));
  if (!added) in.fail(fmt::format("node {} is defined twice", tag), "give every node a unique tag");
  st.mesh.vertices.push_back(x);
}

void add_tet(TextLines& in, GmshState& st, long long tag, std::size_t first_node) {
  std::array<int, 4> tet{};
  for (int k = 0; k < 4; ++k) {
    const long long node = in.integer(first_node + k, fmt::format("node {} of element {}", k + 1, tag));
    const auto it = st.node_index.find(node);
    if (it == st.node_index.end()) {
      in.fail(fmt::format("element {} names node {}, which the $Nodes section does not define", tag, node),
              "export the mesh again with all its nodes, or remove the element");
    }
    tet[k] = it->second;
  }
  st.mesh.tetrahedra.push_back(tet);
  st.mesh.element_line.push_back(in.line());
  st.mesh.element_label.push_back(tag);
}

void expect_end(TextLines& in, std::string_view end) {
  in.expect_next(end);
  if (in.token(0) != end) {
    in.fail(fmt::format("found '{}' where {} was expected", in.text(), end),
            "the section holds more lines than its header counts; export the mesh again");
  }
}

// MSH 2.2: "$Nodes / n / tag x y z …" and "$Elements / m / tag type #tags tags… nodes…".
void read_nodes_v2(TextLines& in, GmshState& st) {
  in.expect_next("the number of nodes");
  const long long n = count_in(in, 0, "the number of nodes");
  for (long long i = 0; i < n; ++i) {
    in.expect_next(fmt::format("node {} of {}", i + 1, n));
    in.require(4, "<node tag> <x> <y> <z>");
    add_node(in, st, in.integer(0, "the node tag"), 1);
  }
  expect_end(in, "$EndNodes");
}

void read_elements_v2(TextLines& in, GmshState& st) {
  in.expect_next("the number of elements");
  const long long n = count_in(in, 0, "the number of elements");
  for (long long i = 0; i < n; ++i) {
    in.expect_next(fmt::format("element {} of {}", i + 1, n));
    in.require(3, "<element tag> <type> <#tags> <tags…> <nodes…>");
    const long long tag = in.integer(0, "the element tag");
    const long long type = in.integer(1, fmt::format("the type of element {}", tag));
    st.has_second_order = st.has_second_order || type == kTet10;
    if (type != kTet4) continue;
    const long long tags = count_in(in, 2, fmt::format("the tag count of element {}", tag));
    const std::size_t first_node = 3 + static_cast<std::size_t>(tags);
    in.require(first_node + 4, "<element tag> 4 <#tags> <tags…> <4 node tags>");
    add_tet(in, st, tag, first_node);
  }
  expect_end(in, "$EndElements");
}

// MSH 4.1: both sections are entity blocks, each with its own header line.
void read_nodes_v4(TextLines& in, GmshState& st) {
  in.expect_next("the $Nodes header");
  in.require(2, "<#entity blocks> <#nodes> <min tag> <max tag>");
  const long long blocks = count_in(in, 0, "the number of node blocks");
  for (long long b = 0; b < blocks; ++b) {
    in.expect_next(fmt::format("node block {} of {}", b + 1, blocks));
    in.require(4, "<entity dim> <entity tag> <parametric 0|1> <#nodes in block>");
    const long long n = count_in(in, 3, "the number of nodes in the block");
    std::vector<long long> tags;
    tags.reserve(static_cast<std::size_t>(n));
    for (long long i = 0; i < n; ++i) {
      in.expect_next(fmt::format("node tag {} of {} in the block", i + 1, n));
      tags.push_back(in.integer(0, "the node tag"));
    }
    // Parametric nodes append u (v, w) after x y z; only x y z are read.
    for (long long i = 0; i < n; ++i) {
      in.expect_next(fmt::format("the coordinates of node {}", tags[i]));
      in.require(3, "<x> <y> <z>");
      add_node(in, st, tags[i], 0);
    }
  }
  expect_end(in, "$EndNodes");
}

void read_elements_v4(TextLines& in, GmshState& st) {
  in.expect_next("the $Elements header");
  in.require(2, "<#entity blocks> <#elements> <min tag> <max tag>");
  const long long blocks = count_in(in, 0, "the number of element blocks");
  for (long long b = 0; b < blocks; ++b) {
    in.expect_next(fmt::format("element block {} of {}", b + 1, blocks));
    in.require(4, "<entity dim> <entity tag> <element type> <#elements in block>");
    const long long type = in.integer(2, "the element type");
    const long long n = count_in(in, 3, "the number of elements in the block");
    st.has_second_order = st.has_second_order || type == kTet10;
    for (long long i = 0; i < n; ++i) {
      in.expect_next(fmt::format("element {} of {} in the block", i + 1, n));
      if (type != kTet4) continue;
      in.require(5, "<element tag> <4 node tags>");
      add_tet(in, st, in.integer(0, "the element tag"), 1);
    }
  }
  expect_end(in, "$EndElements");
}

// Skips a section this reader does not need ($PhysicalNames, $Entities, …).
void skip_section(TextLines& in, std::string_view name) {
  const std::string end = "$End" + std::string(name.substr(1));
  const int start = in.line();
  while (in.next()) {
    if (in.token(0) == end) return;
  }
  throw input_error(
      fmt::format("{}:{}: section {} has no {}; the file is truncated, export it again", in.path(), start, name, end));
}

// Returns the major version (2 or 4) after checking that it is ASCII 2.x or 4.1.
int read_format(TextLines& in) {
  if (!in.next() || in.token(0) != "$MeshFormat") {
    in.fail("this is not a Gmsh mesh (it does not start with $MeshFormat)", "give a .msh file written by Gmsh");
  }
  in.expect_next("the format line");
  in.require(2, "<version> <file type 0=ASCII> <data size>");
  const std::string version(in.token(0));
  if (in.token(1) == "1") in.fail("binary .msh files are not supported", kExportAscii);
  if (in.token(1) != "0") in.fail(fmt::format("unknown file type '{}'", in.token(1)), kExportAscii);
  expect_end(in, "$EndMeshFormat");
  if (version == "2" || version.rfind("2.", 0) == 0) return 2;
  if (version == "4.1") return 4;
  in.fail(fmt::format("MSH version {} is not supported", version), "export the mesh as MSH 4.1 or 2.2 (ASCII)");
}

}  // namespace

TetMesh read_gmsh(const std::string& path) {
  TextLines in(path, false);
  const int version = read_format(in);
  GmshState st;
  st.mesh.file = path;
  while (in.next()) {
    const std::string_view section = in.token(0);
    if (section == "$Nodes") {
      if (st.has_nodes) in.fail("a second $Nodes section", "keep one $Nodes section");
      version == 2 ? read_nodes_v2(in, st) : read_nodes_v4(in, st);
      st.has_nodes = true;
    } else if (section == "$Elements") {
      if (!st.has_nodes) in.fail("$Elements comes before $Nodes", "export the mesh again with Gmsh");
      version == 2 ? read_elements_v2(in, st) : read_elements_v4(in, st);
    } else if (!section.empty() && section[0] == '$') {
      skip_section(in, section);
    } else {
      in.fail(fmt::format("'{}' is outside any section", in.text()), "remove the line or export the mesh again");
    }
  }
  if (st.mesh.tetrahedra.empty()) {
    throw input_error(fmt::format("{}: the mesh has no 4-node tetrahedra (Gmsh element type 4); {}", path,
                                  st.has_second_order
                                      ? "it has 10-node ones: export first-order elements (Mesh.ElementOrder = 1)"
                                      : "mesh the volume (gmsh -3) and export it with its volume elements"));
  }
  return std::move(st.mesh);
}

}  // namespace atssim::scene
