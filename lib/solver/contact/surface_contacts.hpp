#pragma once
// How the simulated surfaces touch, and whether any crossed another, in one
// state: what /contact records per frame for a scene with a contact surface
// (model::ContactSurface, `contact: {self: true}`; docs/output-format.md).
// Measured on the host in double, independently of the device's detection
// (which keeps only the 8 nearest pairs of each primitive, at the start of a
// substep): every vertex-triangle and edge-edge pair closer than the contact
// thickness, incident ones and sheet neighbours (solver/energy/
// sheet_neighbours) excluded, through the kernels' narrow phase
// (common/self_contact.h), and every surface edge against every surface
// triangle it does not touch, for a crossing. Broad phase: solver/contact/
// box_grid (a uniform hashed grid rebuilt per call, its cell widened by the
// thickness) over the triangles, one query per triangle for the vertices
// and edges it owns (each is owned by the first triangle that names it), so
// that a pair is found in one walk; the triangles of one cell take their
// candidates from one list of the triangles near that cell.
#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "solver/energy/sheet_neighbours.hpp"

namespace atssim::solver {

struct SurfaceContacts {
  int vertex_triangle = 0;       // contact pairs (not incident, not sheet neighbours) closer than the thickness
  int edge_edge = 0;             // the same of edges (sharing no vertex)
  double max_penetration = 0.0;  // thickness − the smallest distance of those pairs (0: none)
  int crossings = 0;             // (edge, triangle) pairs sharing no vertex, the edge through the triangle
  int pairs() const { return vertex_triangle + edge_edge; }
};

class SurfaceContactCheck {
 public:
  // `triangles`: the contact surface (particle ids); `thickness` r in m.
  SurfaceContactCheck(std::vector<std::array<int, 3>> triangles, double thickness);

  // xyz: 3 floats per particle (every particle the triangles name). Runs
  // its loops over the surface with oneTBB.
  SurfaceContacts measure(std::span<const float> xyz) const;

  double thickness() const { return thickness_; }
  const std::vector<std::array<int, 3>>& triangles() const { return tris_; }
  const std::vector<std::array<int, 2>>& edges() const { return edges_; }  // unique, (low id, high id)

 private:
  std::vector<std::array<int, 3>> tris_;
  std::vector<std::array<int, 2>> edges_;
  std::vector<int> vertices_;  // the particles on the surface, ascending
  // Per triangle, the vertices (particle ids) and edges (ids into edges_)
  // it owns; -1: none.
  std::vector<std::array<int, 3>> own_vertices_, own_edges_;
  energy::SheetNeighbours sheet_;
  double thickness_ = 0.0;
};

// Whether segment pq passes through triangle abc: p and q strictly on either
// side of its plane, and the line through them meeting the triangle inside or
// on its border (signs of the tetrahedra's volumes). A segment that ends on
// the plane, or lies in it, does not cross; nor does any segment through a
// degenerate triangle.
bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace atssim::solver
