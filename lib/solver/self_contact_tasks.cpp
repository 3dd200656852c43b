#include "solver/self_contact_tasks.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "solver/collision_tasks.hpp"
#include "solver/layout/particle_tables.hpp"

#define ats_float4 ::atssim::solver::Float4
#include "common/self_contact_lists.h"

namespace atssim::solver {

namespace {

using Arg = plan::KernelArg;
using plan::WriteSpan;

constexpr int kListInts = ATS_SC_STRIDE;
constexpr int kNodeBytes = 32;       // two float4 per node
constexpr int kTopLevelNodes = 256;  // levels this small are refitted by one work-item
constexpr int kMotionBlock = ATS_SC_MOTION_BLOCK;
constexpr int kBlockMotionBytes = ATS_SC_BLOCK_FLOATS * 4;
constexpr int kStateInts = ATS_SC_STATE_INTS;
constexpr int kEntryBytes = 32;  // a near-list entry's pair in XPBD's projection: two float4

std::size_t motion_blocks(std::size_t n) { return (n + kMotionBlock - 1) / kMotionBlock; }

// The blocks of ATS_SC_BLOCK leaves that keep or remake their lists
// (common/self_contact_lists.h sc_block_decide).
std::size_t surface_blocks(std::size_t tris) { return (tris + ATS_SC_BLOCK - 1) / ATS_SC_BLOCK; }

std::size_t block_clusters(std::size_t blocks) { return (blocks + ATS_SC_CLUSTER - 1) / ATS_SC_CLUSTER; }

// Per block of leaves its triangles' corners, each once, in ascending order
// (sc_block_motion): start (blocks + 1) and the vertex ids.
std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>> block_corners(const SelfContactLayout& s) {
  std::vector<std::int32_t> start{0}, corners;
  for (std::size_t first = 0; first < s.tris.size(); first += ATS_SC_BLOCK) {
    const std::size_t end = std::min(s.tris.size(), first + ATS_SC_BLOCK);
    std::vector<std::int32_t> block;
    for (std::size_t t = first; t < end; ++t)
      for (int k = 0; k < 3; ++k) block.push_back(std::int32_t(s.tris[t][k]));
    std::sort(block.begin(), block.end());
    block.erase(std::unique(block.begin(), block.end()), block.end());
    corners.insert(corners.end(), block.begin(), block.end());
    start.push_back(std::int32_t(corners.size()));
  }
  return {std::move(start), std::move(corners)};
}

// Per vertex (part 0) or edge (part 4) the block of the leaf that owns it
// (0 where none does: its lists stay empty).
std::vector<std::int32_t> owner_blocks(const SelfContactLayout& s, std::size_t count, int part) {
  std::vector<std::int32_t> block(count, 0);
  for (std::size_t u = 0; u < s.leaves.size(); ++u)
    for (int k = 0; k < 3; ++k)
      if (const int id = s.leaves[u][part + k]; id >= 0) block[std::size_t(id)] = std::int32_t(u / ATS_SC_BLOCK);
  return block;
}

std::vector<std::byte> zeros(std::size_t bytes) { return std::vector<std::byte>(bytes); }

// Per vertex how far `positions` is from `start` (x_t), for the near
// entries' skip (contact/self_contact.cl sc_still_apart).
sched::TaskId add_moved(plan::SubstepPlan& plan, sched::TaskId last, const SelfContactBuffers& b, plan::BufferId start,
                        plan::BufferId positions, int n, sched::Task task) {
  return plan.add_task_after(last, std::move(task),
                             {"sc_moved_since",
                              {0, n},
                              {Arg::of_buffer(positions), Arg::of_buffer(start), Arg::of_buffer(b.moved)},
                              {WriteSpan::per_element(b.moved, 4)}});
}

// After add_moved's task (`last`): the largest `moved` of the surface
// vertices, per block of kMotionBlock and then of all, for the near lists'
// skip as a whole (contact/self_contact.cl sc_list_apart). `name`: the
// tasks' name without its last part.
sched::TaskId add_most_moved(plan::SubstepPlan& plan, sched::TaskId last, const SelfContactBuffers& b, int n,
                             const std::string& name, plan::TaskKind kind, int iteration, int block) {
  const int blocks = static_cast<int>(motion_blocks(static_cast<std::size_t>(n)));
  last = plan.add_task_after(
      last, plan::make_task(name + "/moved_blocks", kind, iteration, block),
      {"sc_moved_blocks",
       {0, blocks},
       {Arg::of_buffer(b.moved), Arg::of_buffer(b.incidence), Arg::of_int(n), Arg::of_buffer(b.moved_blocks)},
       {WriteSpan::per_element(b.moved_blocks, 4)}});
  return plan.add_task_after(last, plan::make_task(name + "/moved_max", kind, iteration, block),
                             {"sc_moved_max",
                              {0, 1},
                              {Arg::of_buffer(b.moved_blocks), Arg::of_int(blocks), Arg::of_buffer(b.most)},
                              {WriteSpan::per_element(b.most, 4)}});
}

}  // namespace

SelfContactBuffers add_self_contact_buffers(plan::SubstepPlan& plan, const SimLayout& layout,
                                            const ColliderBuffers& colliders) {
  const SelfContactLayout& s = layout.self_contact;
  using plan::BufferRole;
  SelfContactBuffers b;
  const std::size_t n = s.enabled ? layout.x.size() : 0;
  b.tris = plan.add_buffer("sc_tris", BufferRole::topology, plan::bytes_of(s.tris));
  b.edges = plan.add_buffer("sc_edges", BufferRole::topology, plan::bytes_of(s.edges));
  b.leaves = plan.add_buffer("sc_leaves", BufferRole::topology, plan::bytes_of(s.leaves));
  b.levels = plan.add_buffer("sc_levels", BufferRole::topology, plan::bytes_of(s.levels));
  b.incidence = plan.add_buffer("sc_incidence", BufferRole::topology, plan::bytes_of(s.incidence));
  // The lists are kept from one substep and frame to the next, per block of
  // leaves, while its motion against its neighbours allows
  // (common/self_contact_lists.h); they, each block's rho at x_det, x_det
  // and sc_state are carried with the positions (and kept in a checkpoint),
  // so that a reset goes on with the lists it had. The tree is refitted
  // whenever a block makes its lists.
  const std::size_t blocks = s.enabled ? surface_blocks(s.tris.size()) : 0;
  b.nodes = plan.add_buffer("sc_nodes", BufferRole::cache, zeros(std::size_t(s.node_count()) * kNodeBytes));
  b.vt = plan.add_buffer("sc_vt", BufferRole::carried, zeros(n * kListInts * 4));
  b.tv = plan.add_buffer("sc_tv", BufferRole::carried, zeros(s.tris.size() * kListInts * 4));
  b.ee = plan.add_buffer("sc_ee", BufferRole::carried, zeros(s.edges.size() * kListInts * 4));
  b.x_det = plan.add_buffer("sc_x_det", BufferRole::carried, zeros(n * kParticleBytes));
  b.state = plan.add_buffer("sc_state", BufferRole::carried, zeros(s.enabled ? kStateInts * 4 : 0));
  b.block_rho0 = plan.add_buffer("sc_block_rho0", BufferRole::carried, zeros(blocks * 4));
  b.block_rho = plan.add_buffer("sc_block_rho", BufferRole::scratch, zeros(blocks * 4));
  b.block_make = plan.add_buffer("sc_block_make", BufferRole::scratch, zeros(blocks * 4));
  b.vertex_block = plan.add_buffer("sc_vertex_block", BufferRole::topology,
                                   plan::bytes_of(s.enabled ? owner_blocks(s, n, 0) : std::vector<std::int32_t>{}));
  b.edge_block =
      plan.add_buffer("sc_edge_block", BufferRole::topology,
                      plan::bytes_of(s.enabled ? owner_blocks(s, s.edges.size(), 4) : std::vector<std::int32_t>{}));
  b.bound = plan.add_buffer("sc_bound", BufferRole::scratch, zeros(n * 4));
  b.x_out = plan.add_buffer("sc_x_out", BufferRole::scratch, zeros(n * kParticleBytes));
  b.moved = plan.add_buffer("sc_moved", BufferRole::scratch, zeros(n * 4));
  b.moved_blocks = plan.add_buffer("sc_moved_blocks", BufferRole::scratch, zeros(motion_blocks(n) * 4));
  b.most = plan.add_buffer("sc_most_moved", BufferRole::scratch, zeros(s.enabled ? 4 : 0));
  b.motion = plan.add_buffer("sc_motion", BufferRole::scratch, zeros(blocks * kBlockMotionBytes));
  const auto [corner_start, corners] =
      s.enabled ? block_corners(s) : std::pair<std::vector<std::int32_t>, std::vector<std::int32_t>>{};
  b.corner_start = plan.add_buffer("sc_corner_start", BufferRole::topology, plan::bytes_of(corner_start));
  b.corners = plan.add_buffer("sc_corners", BufferRole::topology, plan::bytes_of(corners));
  b.clusters = plan.add_buffer("sc_clusters", BufferRole::scratch, zeros(block_clusters(blocks) * 6 * 4));
  b.colliders = colliders.records >= 0 || !s.enabled ? colliders : add_collider_buffers(plan, layout);
  b.vt_d = plan.add_buffer("sc_vt_d", BufferRole::scratch, zeros(n * kListInts * 4));
  b.tv_d = plan.add_buffer("sc_tv_d", BufferRole::scratch, zeros(s.tris.size() * kListInts * 4));
  b.ee_d = plan.add_buffer("sc_ee_d", BufferRole::scratch, zeros(s.edges.size() * kListInts * 4));
  b.vt_reach = plan.add_buffer("sc_vt_reach", BufferRole::scratch, zeros(n * 4));
  b.tv_reach = plan.add_buffer("sc_tv_reach", BufferRole::scratch, zeros(s.tris.size() * 4));
  b.ee_reach = plan.add_buffer("sc_ee_reach", BufferRole::scratch, zeros(s.edges.size() * 4));
  b.vt_listed = plan.add_buffer("sc_vt_listed", BufferRole::carried, zeros(n * 4));
  b.tv_listed = plan.add_buffer("sc_tv_listed", BufferRole::carried, zeros(s.tris.size() * 4));
  b.ee_listed = plan.add_buffer("sc_ee_listed", BufferRole::carried, zeros(s.edges.size() * 4));
  b.tv_count = plan.add_buffer("sc_tv_count", BufferRole::scratch, zeros(s.tris.size() * 4));
  b.ee_count = plan.add_buffer("sc_ee_count", BufferRole::scratch, zeros(s.edges.size() * 4));
  b.vt_count = plan.add_buffer("sc_vt_count", BufferRole::scratch, zeros(n * 4));
  b.vt_total = plan.add_buffer("sc_vt_total", BufferRole::scratch, zeros(n * 4));
  b.vt_near = plan.add_buffer("sc_vt_near", BufferRole::scratch, zeros(n * kListInts * 4));
  b.tv_near = plan.add_buffer("sc_tv_near", BufferRole::scratch, zeros(s.tris.size() * kListInts * 4));
  b.ee_near = plan.add_buffer("sc_ee_near", BufferRole::scratch, zeros(s.edges.size() * kListInts * 4));
  return b;
}

sched::TaskId add_self_contact_detection(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                         const SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions) {
  const SelfContactLayout& s = layout.self_contact;
  if (!s.enabled) return last;
  const int n = static_cast<int>(layout.x.size());
  const int tris = static_cast<int>(s.tris.size());
  const auto detect = [](const std::string& name) { return plan::make_task(name, plan::TaskKind::detection); };
  // Per block of leaves whether it makes its lists anew this substep
  // (common/self_contact_lists.h sc_block_decide): the boxes of its corners,
  // their displacements since x_det and their predicted steps; each block's
  // erosion and radius needed against the blocks near it; whether any makes
  // them. The refit and the walks do nothing where none does.
  const int blocks = static_cast<int>(surface_blocks(std::size_t(tris)));
  const sched::TaskId motion =
      plan.add_task_after(last, detect("detect/motion"),
                          {"sc_motion",
                           {0, blocks},
                           {Arg::of_buffer(b.x_det), Arg::of_buffer(start), Arg::of_buffer(positions),
                            Arg::of_buffer(b.corner_start), Arg::of_buffer(b.corners), Arg::of_buffer(b.motion)},
                           {WriteSpan::per_element(b.motion, kBlockMotionBytes)}});
  const int clusters = static_cast<int>(block_clusters(std::size_t(blocks)));
  last = plan.add_task_after(motion, detect("detect/clusters"),
                             {"sc_clusters",
                              {0, clusters},
                              {Arg::of_buffer(b.motion), Arg::of_int(blocks), Arg::of_buffer(b.clusters)},
                              {WriteSpan::per_element(b.clusters, 6 * 4)}});
  last = plan.add_task_after(last, detect("detect/decide_blocks"),
                             {"sc_decide_block",
                              {0, blocks},
                              {Arg::of_buffer(b.motion), Arg::of_buffer(b.clusters), Arg::of_int(blocks),
                               Arg::of_float(s.thickness), Arg::of_float(s.query_radius), Arg::of_buffer(b.block_rho0),
                               Arg::of_buffer(b.block_rho), Arg::of_buffer(b.block_make)},
                              {WriteSpan::per_element(b.block_rho, 4), WriteSpan::per_element(b.block_make, 4)}});
  last = plan.add_task_after(last, detect("detect/decide_any"),
                             {"sc_decide_any_task",
                              {0, 1},
                              {Arg::of_buffer(b.block_make), Arg::of_int(blocks), Arg::of_float(s.query_radius),
                               Arg::of_buffer(b.block_rho), Arg::of_buffer(b.block_rho0), Arg::of_buffer(b.state)},
                              {WriteSpan::whole_buffer(b.block_rho0), WriteSpan::whole_buffer(b.state)}});
  const sched::TaskId snap =
      plan.add_task_after(last, detect("detect/snap"),
                          {"sc_snap",
                           {0, n},
                           {Arg::of_buffer(start), Arg::of_buffer(b.x_det), Arg::of_buffer(b.state)},
                           {particle_write(b.x_det)}});
  // BVH refit at x_t, bottom up (He et al. 2025 Fig. 2: "BVH updates").
  last = plan.add_task_after(
      snap, detect("detect/leaves"),
      {"sc_leaf_boxes",
       {0, tris},
       {Arg::of_buffer(start), Arg::of_buffer(b.tris), Arg::of_buffer(b.nodes), Arg::of_buffer(b.state)},
       {WriteSpan::per_element(b.nodes, kNodeBytes)}});
  const int root = s.root();
  int level = 1;
  for (; level <= root && s.levels[level + 1] - s.levels[level] > kTopLevelNodes; ++level) {
    const int count = s.levels[level + 1] - s.levels[level];
    last =
        plan.add_task_after(last, detect(fmt::format("detect/level{}", level)),
                            {"sc_refit_level",
                             {0, count},
                             {Arg::of_buffer(b.nodes), Arg::of_int(s.levels[level]), Arg::of_int(s.levels[level - 1]),
                              Arg::of_int(s.levels[level] - s.levels[level - 1]), Arg::of_buffer(b.state)},
                             {WriteSpan::per_element(b.nodes, kNodeBytes, s.levels[level])}});
  }
  if (level <= root) {
    last = plan.add_task_after(last, detect("detect/top"),
                               {"sc_refit_top",
                                {0, 1},
                                {Arg::of_buffer(b.nodes), Arg::of_buffer(b.levels), Arg::of_int(level),
                                 Arg::of_int(root), Arg::of_buffer(b.state)},
                                {WriteSpan::whole_buffer(b.nodes)}});
  }
  const sched::TaskId refit = last;
  // The pairs of the primitives each leaf owns (one owner each): its
  // triangle's vertices, its vertices' triangles, its edges' edges; one walk
  // per group of ATS_SC_GROUP leaves (common/self_contact_bvh.h
  // sc_query_group), which writes the lists of its leaves' primitives.
  const int groups = (tris + ATS_SC_GROUP - 1) / ATS_SC_GROUP;
  const auto owned = [&](int first, int arity) {
    auto table = std::make_shared<std::vector<std::int32_t>>();
    table->reserve(std::size_t(groups) * ATS_SC_GROUP * arity);
    for (int u = 0; u < groups * ATS_SC_GROUP; ++u)
      for (int k = 0; k < arity; ++k) table->push_back(u >= tris ? -1 : (first < 0 ? u : s.leaves[u][first + k]));
    return table;
  };
  const sched::TaskId pairs = plan.add_task_after(
      refit, detect("detect/pairs"),
      {"sc_query_groups",
       {0, groups},
       {Arg::of_buffer(start), Arg::of_buffer(b.incidence), Arg::of_int(n), Arg::of_buffer(b.tris),
        Arg::of_buffer(b.edges), Arg::of_buffer(b.leaves), Arg::of_buffer(b.nodes), Arg::of_buffer(b.levels),
        Arg::of_int(root), Arg::of_int(tris), Arg::of_buffer(b.state), Arg::of_buffer(b.block_make),
        Arg::of_buffer(b.vt), Arg::of_buffer(b.tv), Arg::of_buffer(b.ee)},
       {WriteSpan::per_index(b.vt, kListInts * 4, 3 * ATS_SC_GROUP, owned(0, 3)),
        WriteSpan::per_index(b.tv, kListInts * 4, ATS_SC_GROUP, owned(-1, 1)),
        WriteSpan::per_index(b.ee, kListInts * 4, 3 * ATS_SC_GROUP, owned(4, 3))}});
  // Every listed pair's distance at x_t once (each list's entries), then
  // the bound per vertex from them, then the entries the iterations can meet
  // (common/self_contact_lists.h sc_near_vertex): a list holds up to 8 pairs
  // within the query radius, a few of which come within the thickness in one
  // substep.
  const int edges = static_cast<int>(s.edges.size());
  // Each writes its lists (`out`), and a packed float or int per list in
  // each of `packed`.
  const auto per_list = [&](const std::string& name, const char* function, int count, std::vector<Arg> args,
                            plan::BufferId out, const std::vector<plan::BufferId>& packed,
                            plan::BufferId distances = -1) {
    std::vector<WriteSpan> writes{WriteSpan::per_element(out, kListInts * 4)};
    for (const plan::BufferId p : packed) writes.push_back(WriteSpan::per_element(p, 4));
    // The near lists move their entries' distances to the front (sc_near_store).
    if (distances >= 0) writes.push_back(WriteSpan::per_element(distances, kListInts * 4));
    last = plan.add_task_after(last, detect(name), {function, {0, count}, std::move(args), std::move(writes)});
  };
  last = pairs;
  per_list("detect/distances_vertices", "sc_vertex_distances_task", n,
           {Arg::of_buffer(start), Arg::of_buffer(b.tris), Arg::of_buffer(b.vt), Arg::of_buffer(b.state),
            Arg::of_buffer(b.vertex_block), Arg::of_buffer(b.block_rho), Arg::of_buffer(b.block_make),
            Arg::of_buffer(b.vt_d), Arg::of_buffer(b.vt_reach), Arg::of_buffer(b.vt_listed)},
           b.vt_d, {b.vt_reach, b.vt_listed});
  per_list("detect/distances_triangles", "sc_triangle_distances_task", tris,
           {Arg::of_buffer(start), Arg::of_buffer(b.tris), Arg::of_buffer(b.tv), Arg::of_buffer(b.state),
            Arg::of_buffer(b.block_rho), Arg::of_buffer(b.block_make), Arg::of_buffer(b.tv_d),
            Arg::of_buffer(b.tv_reach), Arg::of_buffer(b.tv_listed)},
           b.tv_d, {b.tv_reach, b.tv_listed});
  per_list("detect/distances_edges", "sc_edge_distances_task", edges,
           {Arg::of_buffer(start), Arg::of_buffer(b.edges), Arg::of_buffer(b.ee), Arg::of_buffer(b.state),
            Arg::of_buffer(b.edge_block), Arg::of_buffer(b.block_rho), Arg::of_buffer(b.block_make),
            Arg::of_buffer(b.ee_d), Arg::of_buffer(b.ee_reach), Arg::of_buffer(b.ee_listed)},
           b.ee_d, {b.ee_reach, b.ee_listed});
  const sched::TaskId bound = plan.add_task_after(
      last, detect("detect/bound"),
      {"sc_bound",
       {0, n},
       {Arg::of_buffer(b.incidence), Arg::of_int(n), Arg::of_buffer(b.vt_reach), Arg::of_buffer(b.tv_reach),
        Arg::of_buffer(b.ee_reach), Arg::of_float(s.gamma), Arg::of_buffer(b.bound)},
       {WriteSpan::per_element(b.bound, 4)}});
  last = bound;
  const float r = s.thickness;
  per_list("detect/near_triangles", "sc_near_triangles", tris,
           {Arg::of_buffer(b.tris), Arg::of_buffer(b.tv), Arg::of_buffer(b.tv_d), Arg::of_buffer(b.bound),
            Arg::of_float(r), Arg::of_buffer(b.tv_listed), Arg::of_buffer(b.tv_near), Arg::of_buffer(b.tv_count)},
           b.tv_near, {b.tv_count}, b.tv_d);
  per_list("detect/near_edges", "sc_near_edges", edges,
           {Arg::of_buffer(b.edges), Arg::of_buffer(b.ee), Arg::of_buffer(b.ee_d), Arg::of_buffer(b.bound),
            Arg::of_float(r), Arg::of_buffer(b.ee_listed), Arg::of_buffer(b.ee_near), Arg::of_buffer(b.ee_count)},
           b.ee_near, {b.ee_count}, b.ee_d);
  // last: it counts the near entries of each vertex's triangles and edges
  per_list("detect/near_vertices", "sc_near_vertices", n,
           {Arg::of_buffer(b.incidence), Arg::of_int(n), Arg::of_buffer(b.tris), Arg::of_buffer(b.vt),
            Arg::of_buffer(b.vt_d), Arg::of_buffer(b.bound), Arg::of_float(r), Arg::of_buffer(b.tv_count),
            Arg::of_buffer(b.ee_count), Arg::of_buffer(b.vt_listed), Arg::of_buffer(b.vt_near),
            Arg::of_buffer(b.vt_count), Arg::of_buffer(b.vt_total)},
           b.vt_near, {b.vt_count, b.vt_total}, b.vt_d);
  return plan.add_task_after(
      last, plan::make_task("contact/first_guess", plan::TaskKind::collision),
      {"sc_clamp",
       {0, n},
       with_colliders({Arg::of_buffer(positions), Arg::of_buffer(start), Arg::of_buffer(b.bound)}, layout, b.colliders),
       {particle_write(positions)}});
}

std::vector<plan::KernelArg> self_contact_args(const SimLayout& layout, const SelfContactBuffers& b, double inertia_h) {
  const SelfContactLayout& s = layout.self_contact;
  return {Arg::of_buffer(b.tris),
          Arg::of_buffer(b.edges),
          Arg::of_buffer(b.incidence),
          Arg::of_buffer(b.vt_near),
          Arg::of_buffer(b.tv_near),
          Arg::of_buffer(b.ee_near),
          Arg::of_buffer(b.bound),
          Arg::of_int(static_cast<int>(layout.x.size())),
          Arg::of_float(static_cast<float>(self_contact_k(s, inertia_h))),
          Arg::of_float(s.thickness),
          Arg::of_int(s.enabled ? 1 : 0)};
}

sched::TaskId add_self_contact_clamp(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                     const SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions,
                                     int iteration, plan::BufferId moved) {
  if (!layout.self_contact.enabled) return last;
  const int n = static_cast<int>(layout.x.size());
  // With `moved` (XPBD, whose iteration ends with its collider task): not
  // out of the colliders here (contact/self_contact.cl sc_clamp_moved).
  std::vector<Arg> args{Arg::of_buffer(positions), Arg::of_buffer(start), Arg::of_buffer(b.bound)};
  std::vector<WriteSpan> writes{particle_write(positions)};
  if (moved >= 0) {
    args.push_back(Arg::of_buffer(moved));
    writes.push_back(WriteSpan::per_element(moved, 4));
  } else {
    args = with_colliders(std::move(args), layout, b.colliders);
  }
  return plan.add_task_after(
      last,
      plan::make_task(fmt::format("it{}/collision/bound", iteration + 1), plan::TaskKind::collision, iteration, 2),
      {moved >= 0 ? "sc_clamp_moved" : "sc_clamp", {0, n}, std::move(args), std::move(writes)});
}

void add_self_contact_projection_buffers(plan::SubstepPlan& plan, const SimLayout& layout, SelfContactBuffers& b) {
  const SelfContactLayout& s = layout.self_contact;
  const std::size_t n = s.enabled ? layout.x.size() : 0, tris = s.enabled ? s.tris.size() : 0,
                    edges = s.enabled ? s.edges.size() : 0;
  using plan::BufferRole;
  b.vt_l = plan.add_buffer("sc_vt_lambda", BufferRole::scratch, zeros(n * kEntryBytes * ATS_SC_CAPACITY));
  b.tv_l = plan.add_buffer("sc_tv_lambda", BufferRole::scratch, zeros(tris * kEntryBytes * ATS_SC_CAPACITY));
  b.ee_l = plan.add_buffer("sc_ee_lambda", BufferRole::scratch, zeros(edges * kEntryBytes * ATS_SC_CAPACITY));
  b.vt_k = plan.add_buffer("sc_vt_active", BufferRole::scratch, zeros(n * sizeof(std::int32_t)));
  b.tv_k = plan.add_buffer("sc_tv_active", BufferRole::scratch, zeros(tris * sizeof(std::int32_t)));
  b.ee_k = plan.add_buffer("sc_ee_active", BufferRole::scratch, zeros(edges * sizeof(std::int32_t)));
}

sched::TaskId add_self_contact_projection(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                          const SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions,
                                          int iteration) {
  const SelfContactLayout& s = layout.self_contact;
  if (!s.enabled) return last;
  const int n = static_cast<int>(layout.x.size());
  // The constraints' step held within the bound first, then the contact
  // projection on top, unbounded: it separates a pair, and held within a
  // bound that shrinks with the gap it could not reopen one (a pillow vertex
  // pressed into the cloth reached distance 0, where its bound froze it, and
  // the cloth then slid over it).
  // The clamp and each vertex's distance from x_t for the near entries'
  // skip (sc_still_apart), in one pass.
  last = add_self_contact_clamp(plan, last, layout, b, start, positions, iteration, b.moved);
  last = add_most_moved(plan, last, b, n, fmt::format("it{}/collision", iteration + 1), plan::TaskKind::collision,
                        iteration, 2);
  // Per near-list entry the pair's multiplier (each pair evaluated once per
  // list that holds it, not by each of its four vertices:
  // contact/self_contact.cl) and per list how many act, then per vertex.
  const auto entries = [&](const char* part, const char* function, int count, plan::BufferId topology,
                           std::vector<Arg> lists, plan::BufferId out, plan::BufferId active) {
    std::vector<Arg> args{Arg::of_buffer(positions), Arg::of_buffer(b.moved), Arg::of_buffer(b.most),
                          Arg::of_buffer(topology)};
    args.insert(args.end(), lists.begin(), lists.end());
    args.push_back(Arg::of_float(s.thickness));
    args.push_back(Arg::of_buffer(out));
    args.push_back(Arg::of_buffer(active));
    return plan.add_task_after(last,
                               plan::make_task(fmt::format("it{}/collision/surface_pairs/{}", iteration + 1, part),
                                               plan::TaskKind::collision, iteration, 2),
                               {function,
                                {0, count},
                                std::move(args),
                                {WriteSpan::per_element(out, kEntryBytes * ATS_SC_CAPACITY),
                                 WriteSpan::per_element(active, sizeof(std::int32_t))}});
  };
  const sched::TaskId points =
      entries("points", "sc_pair_lambdas_points", n, b.tris,
              {Arg::of_buffer(b.vt_near), Arg::of_buffer(b.vt_d), Arg::of_buffer(b.vt_count)}, b.vt_l, b.vt_k);
  const sched::TaskId triangles =
      entries("triangles", "sc_pair_lambdas_triangles", static_cast<int>(s.tris.size()), b.tris,
              {Arg::of_buffer(b.tv_near), Arg::of_buffer(b.tv_d), Arg::of_buffer(b.tv_count)}, b.tv_l, b.tv_k);
  const sched::TaskId edges =
      entries("edges", "sc_pair_lambdas_edges", static_cast<int>(s.edges.size()), b.edges,
              {Arg::of_buffer(b.ee_near), Arg::of_buffer(b.ee_d), Arg::of_buffer(b.ee_count)}, b.ee_l, b.ee_k);
  const sched::TaskId project = plan.add_task_after(
      edges,
      plan::make_task(fmt::format("it{}/collision/surfaces", iteration + 1), plan::TaskKind::collision, iteration, 3),
      {"sc_project",
       {0, n},
       {Arg::of_buffer(positions), Arg::of_buffer(b.tris), Arg::of_buffer(b.edges), Arg::of_buffer(b.incidence),
        Arg::of_int(n), Arg::of_buffer(b.vt_total), Arg::of_buffer(b.vt_l), Arg::of_buffer(b.tv_l),
        Arg::of_buffer(b.ee_l), Arg::of_buffer(b.vt_k), Arg::of_buffer(b.tv_k), Arg::of_buffer(b.ee_k)},
       {particle_write(positions)}});
  plan.graph.add_edge(points, project);
  plan.graph.add_edge(triangles, project);
  return project;
}

sched::TaskId add_self_contact_friction(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                        SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions,
                                        plan::BufferId velocities, plan::BufferId friction, double h) {
  const SelfContactLayout& s = layout.self_contact;
  const bool material = std::any_of(layout.friction.begin(), layout.friction.end(),
                                    [](const std::array<float, 2>& f) { return f[0] > 0.0f || f[1] > 0.0f; });
  if (!s.enabled || !(s.mu_s > 0.0f || s.mu_k > 0.0f || material)) return last;
  const int n = static_cast<int>(layout.x.size());
  // Per near-list entry the pair's friction and per list how many act, into
  // the buffers XPBD's projection uses during the iterations (free after
  // them), then per vertex.
  if (b.vt_l < 0) add_self_contact_projection_buffers(plan, layout, b);
  const auto entries = [&](const char* part, const char* function, int count, plan::BufferId topology,
                           plan::BufferId list, plan::BufferId distances, plan::BufferId out, plan::BufferId active) {
    return plan.add_task_after(
        last, plan::make_task(fmt::format("contact/friction_pairs/{}", part), plan::TaskKind::friction, -1, 0),
        {function,
         {0, count},
         {Arg::of_buffer(positions), Arg::of_buffer(start), Arg::of_buffer(velocities),
          Arg::of_float(static_cast<float>(h)), Arg::of_buffer(topology), Arg::of_buffer(list),
          Arg::of_buffer(distances), Arg::of_buffer(b.moved), Arg::of_buffer(b.most), Arg::of_float(s.thickness),
          Arg::of_float(s.mu_s), Arg::of_float(s.mu_k), Arg::of_buffer(friction), Arg::of_buffer(out),
          Arg::of_buffer(active)},
         {WriteSpan::per_element(out, kEntryBytes * ATS_SC_CAPACITY),
          WriteSpan::per_element(active, sizeof(std::int32_t))}});
  };
  last = add_moved(plan, last, b, start, positions, n,
                   plan::make_task("contact/friction_pairs/moved", plan::TaskKind::friction, -1, 0));
  last = add_most_moved(plan, last, b, n, "contact/friction_pairs", plan::TaskKind::friction, -1, 0);
  const sched::TaskId points =
      entries("points", "sc_friction_pairs_points", n, b.tris, b.vt_near, b.vt_d, b.vt_l, b.vt_k);
  const sched::TaskId triangles = entries("triangles", "sc_friction_pairs_triangles", static_cast<int>(s.tris.size()),
                                          b.tris, b.tv_near, b.tv_d, b.tv_l, b.tv_k);
  const sched::TaskId edges = entries("edges", "sc_friction_pairs_edges", static_cast<int>(s.edges.size()), b.edges,
                                      b.ee_near, b.ee_d, b.ee_l, b.ee_k);
  last = plan.add_task_after(
      edges, plan::make_task("contact/friction", plan::TaskKind::friction, -1, 1),
      {"sc_friction",
       {0, n},
       {Arg::of_buffer(positions), Arg::of_buffer(b.x_out), Arg::of_buffer(b.tris), Arg::of_buffer(b.edges),
        Arg::of_buffer(b.incidence), Arg::of_int(n), Arg::of_buffer(b.vt_near), Arg::of_buffer(b.vt_l),
        Arg::of_buffer(b.tv_l), Arg::of_buffer(b.ee_l), Arg::of_buffer(b.vt_k), Arg::of_buffer(b.tv_k),
        Arg::of_buffer(b.ee_k)},
       {particle_write(b.x_out)}});
  plan.graph.add_edge(points, last);
  plan.graph.add_edge(triangles, last);
  return plan.add_task_after(last, plan::make_task("contact/friction_apply", plan::TaskKind::copy),
                             {"sc_apply",
                              {0, n},
                              with_colliders({Arg::of_buffer(positions), Arg::of_buffer(b.x_out), Arg::of_buffer(start),
                                              Arg::of_buffer(b.bound)},
                                             layout, b.colliders),
                              {particle_write(positions)}});
}

}  // namespace atssim::solver
