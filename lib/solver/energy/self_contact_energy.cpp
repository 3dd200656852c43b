#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include "solver/energy/self_contact_energy.hpp"

#include "solver/energy/sheet_neighbours.hpp"

#include <algorithm>
#include <set>

namespace atssim::solver::energy {

namespace {

using f64::ats_vec3;

ats_vec3 at(const Eigen::VectorXd& x, int i) { return f64::ats_v3(x[3 * i], x[3 * i + 1], x[3 * i + 2]); }

struct Box {
  Eigen::Vector3d lo, hi;
  bool overlaps(const Box& o, double r) const {
    return (lo.array() <= o.hi.array() + r).all() && (o.lo.array() <= hi.array() + r).all();
  }
};

template <std::size_t N>
Box box_of(const std::array<int, N>& v, const Eigen::VectorXd& x) {
  Box b{x.segment<3>(3 * v[0]), x.segment<3>(3 * v[0])};
  for (std::size_t k = 1; k < N; ++k) {
    b.lo = b.lo.cwiseMin(x.segment<3>(3 * v[k]));
    b.hi = b.hi.cwiseMax(x.segment<3>(3 * v[k]));
  }
  return b;
}

f64::ats_pair_geometry geometry(const SurfacePair& p, const Eigen::VectorXd& x) {
  return p.edge_edge ? f64::ats_edge_edge(at(x, p.v[0]), at(x, p.v[1]), at(x, p.v[2]), at(x, p.v[3]))
                     : f64::ats_point_triangle(at(x, p.v[0]), at(x, p.v[1]), at(x, p.v[2]), at(x, p.v[3]));
}

}  // namespace

std::vector<SurfacePair> surface_pairs(const SurfaceContactTerm& term, const Eigen::VectorXd& x) {
  std::vector<SurfacePair> out;
  if (term.tris.empty()) return out;
  std::set<int> vertex_set;
  for (const auto& t : term.tris) vertex_set.insert(t.begin(), t.end());
  const std::vector<int> vertices(vertex_set.begin(), vertex_set.end());
  std::vector<Box> tri_box, edge_box;
  for (const auto& t : term.tris) tri_box.push_back(box_of(t, x));
  for (const auto& e : term.edges) edge_box.push_back(box_of(e, x));
  const SheetNeighbours sheet(term.tris);
  const SheetNeighbours::Positions pos = [&](int i) { return Eigen::Vector3d(x.segment<3>(3 * i)); };
  for (int v : vertices) {
    const Box pb{x.segment<3>(3 * v), x.segment<3>(3 * v)};
    for (std::size_t t = 0; t < term.tris.size(); ++t) {
      const auto& f = term.tris[t];
      if (f[0] == v || f[1] == v || f[2] == v || !pb.overlaps(tri_box[t], term.r)) continue;
      const SurfacePair p{false, {v, f[0], f[1], f[2]}};
      const f64::ats_pair_geometry g = geometry(p, x);
      if (g.d < term.r && !sheet.vertex_triangle(v, f, {g.diff.x, g.diff.y, g.diff.z}, pos)) out.push_back(p);
    }
  }
  for (std::size_t e = 0; e < term.edges.size(); ++e) {
    const auto& a = term.edges[e];
    for (std::size_t f = e + 1; f < term.edges.size(); ++f) {
      const auto& b = term.edges[f];
      if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) continue;
      if (!edge_box[e].overlaps(edge_box[f], term.r)) continue;
      const SurfacePair p{true, {a[0], a[1], b[0], b[1]}};
      const f64::ats_pair_geometry g = geometry(p, x);
      if (g.d < term.r && !sheet.edge_edge(a, b, {g.diff.x, g.diff.y, g.diff.z}, pos)) out.push_back(p);
    }
  }
  return out;
}

double surface_contact_energy(const SurfaceContactTerm& term, const Eigen::VectorXd& x) {
  double e = 0.0;
  for (const SurfacePair& p : surface_pairs(term, x)) e += f64::ats_pair_energy(geometry(p, x), term.k, term.r);
  return e;
}

void add_surface_contact_gradient(const SurfaceContactTerm& term, const Eigen::VectorXd& x, Eigen::VectorXd& g) {
  for (const SurfacePair& p : surface_pairs(term, x)) {
    const f64::ats_pair_geometry geo = geometry(p, x);
    for (int j = 0; j < 4; ++j) {
      const ats_vec3 d = f64::ats_pair_gradient(geo, term.k, term.r, j);
      g.segment<3>(3 * p.v[j]) += Eigen::Vector3d(d.x, d.y, d.z);
    }
  }
}

void add_surface_contact_hessian(const IncrementalPotential& p, const Eigen::VectorXd& x,
                                 std::vector<Eigen::Triplet<double>>& out) {
  const SurfaceContactTerm& term = p.surface_contact;
  for (const SurfacePair& pair : surface_pairs(term, x)) {
    const f64::ats_pair_geometry geo = geometry(pair, x);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const int a = pair.v[i], b = pair.v[j];
        if (!p.is_free(a) || !p.is_free(b)) continue;
        const f64::ats_mat3 m = f64::ats_pair_hessian(geo, term.k, term.r, i, j);
        for (int r = 0; r < 3; ++r) {
          const double row[3] = {m.r[r].x, m.r[r].y, m.r[r].z};
          for (int c = 0; c < 3; ++c) out.emplace_back(3 * a + r, 3 * b + c, row[c]);
        }
      }
    }
  }
}

}  // namespace atssim::solver::energy
