#include "solver/contact/collider_buffer.hpp"

#include <algorithm>
#include <cstring>

namespace atssim::solver {

static_assert(sizeof(ats_collider_c) == 192, "the collider record is 48 floats in kernels and host");
static_assert(sizeof(ats_bvh_node) == 32 && sizeof(ats_mesh_triangle) == 128,
              "BVH nodes and mesh triangles pack into collider records");
static_assert(static_cast<int>(scene::ColliderShape::plane) == ATS_COLLIDER_PLANE &&
                  static_cast<int>(scene::ColliderShape::sphere) == ATS_COLLIDER_SPHERE &&
                  static_cast<int>(scene::ColliderShape::capsule) == ATS_COLLIDER_CAPSULE &&
                  static_cast<int>(scene::ColliderShape::box) == ATS_COLLIDER_BOX &&
                  static_cast<int>(scene::ColliderShape::mesh) == ATS_COLLIDER_MESH,
              "ColliderShape is in ATS_COLLIDER_* order");

namespace {

void put(float* out, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) out[k] = float(v[k]);
  out[3] = 0.0f;
}

void put3(float* out, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) out[k] = float(v[k]);
}

// Appends `items` to `records`, padded to whole records; returns the index of
// the first record they occupy.
template <typename T>
int append_packed(std::vector<ats_collider_c>& records, const std::vector<T>& items) {
  const int first = static_cast<int>(records.size());
  const std::size_t bytes = items.size() * sizeof(T);
  records.resize(records.size() + (bytes + sizeof(ats_collider_c) - 1) / sizeof(ats_collider_c), ats_collider_c{});
  if (bytes > 0) std::memcpy(static_cast<void*>(records.data() + first), items.data(), bytes);
  return first;
}

std::vector<ats_bvh_node> device_nodes(const model::ObstacleBvh& bvh) {
  std::vector<ats_bvh_node> out;
  for (const model::BvhNode& n : bvh.nodes) {
    ats_bvh_node d{};
    put3(d.lo, n.lo);
    put3(d.hi, n.hi);
    d.first = n.first;
    d.count = n.count;
    out.push_back(d);
  }
  return out;
}

// In BVH leaf order, so that a leaf's entries are its triangles.
std::vector<ats_mesh_triangle> device_triangles(const model::ObstacleMesh& m) {
  std::vector<ats_mesh_triangle> out;
  for (int t : m.bvh.order) {
    ats_mesh_triangle d{};
    for (int k = 0; k < 3; ++k) {
      put3(d.p + 3 * k, m.vertices[m.triangles[t][k]]);
      put3(d.edge + 3 * k, m.edge_normal[t][k]);
      put3(d.vertex + 3 * k, m.vertex_normal[m.triangles[t][k]]);
    }
    put3(d.n, m.face_normal[t]);
    out.push_back(d);
  }
  return out;
}

// How far a mesh query looks: just past the thickness for an open mesh
// (nothing farther has contact); for a closed one also a quarter of its
// smallest extent, so that a particle that went deeper than the thickness
// is still pushed out.
float mesh_reach(const model::Collider& c) {
  if (!c.mesh->closed || c.mesh->bvh.nodes.empty()) return float(1.5 * c.thickness);
  const Eigen::Vector3d extent = c.mesh->bvh.nodes[0].hi - c.mesh->bvh.nodes[0].lo;
  return float(c.thickness + std::max(c.thickness, 0.25 * extent.minCoeff()));
}

}  // namespace

ats_collider_c collider_record(const model::Collider& c) {
  ats_collider_c r{};
  r.shape = float(static_cast<int>(c.shape));  // scene::ColliderShape follows ATS_COLLIDER_* order
  r.thickness = float(c.thickness);
  // Unset: -1, the particle's material friction decides (common/contact_steps.cl).
  r.mu_s = c.friction_set ? float(c.static_friction) : -1.0f;
  r.mu_k = c.friction_set ? float(c.kinetic_friction) : -1.0f;
  put(r.c, c.point);
  put(r.n, c.shape == scene::ColliderShape::capsule ? c.end : c.normal);
  for (int k = 0; k < 3; ++k) put(r.axes + 4 * k, c.axes.row(k).transpose());
  put(r.extent, c.half);
  r.radius = float(c.radius);
  r.stiffness = float(c.stiffness);
  put(r.pivot, c.pivot);
  if (c.mesh) {
    r.mesh[2] = c.mesh->closed ? 1.0f : 0.0f;
    r.mesh[3] = mesh_reach(c);
  }
  return r;
}

ColliderBuffer collider_buffer(const std::vector<model::Collider>& colliders) {
  ColliderBuffer out;
  out.count = static_cast<int>(colliders.size());
  for (const model::Collider& c : colliders) out.records.push_back(collider_record(c));
  // Each mesh's slot among a particle's near lists (common/mesh_near.h).
  int slots = 0;
  for (ats_collider_c& r : out.records) {
    if (static_cast<int>(r.shape) == ATS_COLLIDER_MESH) r.near_slot = float(slots++);
  }
  for (ats_collider_c& r : out.records) r.near_slots = float(slots);
  for (int i = 0; i < out.count; ++i) {
    const model::Collider& c = colliders[i];
    if (!c.mesh) continue;
    const int nodes = append_packed(out.records, device_nodes(c.mesh->bvh));
    const int tris = append_packed(out.records, device_triangles(*c.mesh));
    out.records[i].mesh[0] = float(nodes - i);
    out.records[i].mesh[1] = float(tris - i);
  }
  return out;
}

}  // namespace atssim::solver
