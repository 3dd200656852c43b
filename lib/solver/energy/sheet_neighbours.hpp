#pragma once
// Sheet neighbours on the host, in double (common/self_contact.h
// ats_pair_in_plane; the kernels' own test is common/self_contact_bvh.h
// sc_sheet_*): a vertex-triangle or edge-edge pair of the contact surface
// whose primitives are joined (a vertex of one and a vertex of the other
// corners of one surface triangle) and whose offset lies within 30 degrees
// of the plane of its triangles (the triangle; every triangle of either
// edge) is two neighbours side by side in one sheet: no contact pair.
// For the Newton reference's brute force (self_contact_energy) and the
// per-frame record (solver/contact/surface_contacts).
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace atssim::solver::energy {

class SheetNeighbours {
 public:
  using Positions = std::function<Eigen::Vector3d(int)>;  // particle id -> position

  SheetNeighbours() = default;
  explicit SheetNeighbours(const std::vector<std::array<int, 3>>& tris);

  // Vertex v and triangle f, diff the pair's offset (v less its closest
  // point on f).
  bool vertex_triangle(int v, const std::array<int, 3>& f, const Eigen::Vector3d& diff, const Positions& at) const;
  // Edges a and b, diff the offset between their closest points.
  bool edge_edge(const std::array<int, 2>& a, const std::array<int, 2>& b, const Eigen::Vector3d& diff,
                 const Positions& at) const;

 private:
  // v and one of the particles c are corners of one triangle.
  bool joined(int v, const std::array<int, 3>& c) const;
  // diff within 30 degrees of the plane of every triangle of edge e.
  bool edge_in_plane(const std::array<int, 2>& e, const Eigen::Vector3d& diff, const Positions& at) const;

  std::vector<std::array<int, 3>> tris_;
  std::vector<std::vector<int>> incident_;  // per particle, its triangles
};

}  // namespace atssim::solver::energy
