// Broad phase of contact between simulated surfaces: the device's BVH
// (built once by solver/layout/self_contact_layout, refitted every substep,
// walked by kernels/contact/self_contact.cl; mirrored on the host in
// broad_phase/bvh_pairs.hpp) against a uniform spatial hash rebuilt every
// substep (Teschner et al. 2003; broad_phase/hash_pairs.hpp), for the same
// three queries and the same pairs, on a folded, crumpled cloth sheet
// (broad_phase/crumpled_sheet.hpp), or on the surfaces of a scene at one
// frame of a run (--scene, --state, --frame: e.g. the paper funnel's
// pressed layers). Host float, 1 thread and TBB threads.
//
//   bench_broad_phase [--sizes 128,256,512] [--cells 1,2,4] [--threads 1,2] [--rounds 5] [--brute-max 128]
//   bench_broad_phase --scene scenes/paper/funnel.yaml --state funnel.h5 --frame 16 [--cells 2] [--threads 1]
//
// Every method runs once per round, interleaved; the medians are printed.
// Before timing, the pair sets of every method are compared (and with a
// brute force up to --brute-max); a mismatch prints FAIL and exits 1.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <CLI/CLI.hpp>

#include "broad_phase/bvh_pairs.hpp"
#include "broad_phase/crumpled_sheet.hpp"
#include "broad_phase/hash_pairs.hpp"
#include "io/result_reader.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::bench;
using Clock = std::chrono::steady_clock;

namespace {

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// body(begin, end, lists) over [0, count): directly with one thread, else in
// chunks on the arena, each thread into its own lists.
struct Runner {
  int threads = 1;
  tbb::task_arena* arena = nullptr;
  tbb::enumerable_thread_specific<PairLists>* lists = nullptr;
  PairLists* serial = nullptr;

  template <typename Body>
  void each(int count, Body&& body) const {
    if (threads == 1) return body(0, count, *serial);
    arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, count, 1024),
                        [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end(), lists->local()); });
    });
  }
  template <typename Body>
  void each_item(int count, Body&& body) const {  // no pair output
    each(count, [&](int b, int e, PairLists&) { body(b, e); });
  }
  void clear() const {
    if (serial) serial->clear();
    if (lists)
      for (PairLists& l : *lists) l.clear();
  }
  PairLists gathered() const {
    PairLists all;
    if (threads == 1) {
      all = *serial;
    } else {
      for (const PairLists& l : *lists) all.append(l);
    }
    all.sort();
    return all;
  }
};

struct Timing {
  std::vector<double> build, query;
  std::vector<double> part[3];  // the query's share per vertex, per triangle, per edge
  void clear() {
    build.clear();
    query.clear();
    for (auto& p : part) p.clear();
  }
};

// Runs the three queries, timing each.
template <typename V, typename T, typename E>
void timed_queries(Timing& t, V&& vertices, T&& triangles, E&& edges) {
  const auto start = Clock::now();
  auto at = start;
  vertices();
  t.part[0].push_back(ms_since(at));
  at = Clock::now();
  triangles();
  t.part[1].push_back(ms_since(at));
  at = Clock::now();
  edges();
  t.part[2].push_back(ms_since(at));
  t.query.push_back(ms_since(start));
}

struct Scene {
  solver::SelfContactLayout layout;
  std::vector<ats_vec3> x;
  std::vector<Float4> xf;  // the same, as the kernels' float4
  float r = 0.0f;
  int n() const { return static_cast<int>(x.size()); }
  int tris() const { return static_cast<int>(layout.tris.size()); }
  int edges() const { return static_cast<int>(layout.edges.size()); }
};

// One substep of the BVH: refit (leaf boxes, then level by level), three queries.
void bvh_refit_timed(const Scene& sc, std::vector<Float4>& nodes, const Runner& run, Timing& t) {
  const auto& s = sc.layout;
  auto start = Clock::now();
  run.each_item(sc.tris(), [&](int b, int e) { bvh_leaf_boxes(s, sc.xf, nodes, b, e); });
  for (int l = 1; l <= s.root(); ++l) {
    const int size = bvh_level_size(s, l);
    if (size > 256) {
      run.each_item(size, [&](int b, int e) { bvh_refit_level(s, nodes, l, b, e); });
    } else {
      bvh_refit_level(s, nodes, l, 0, size);  // sc_refit_top: one work-item for the small levels
    }
  }
  t.build.push_back(ms_since(start));
}

void bvh_step(const Scene& sc, std::vector<Float4>& nodes, const Runner& run, Timing& t) {
  run.clear();
  bvh_refit_timed(sc, nodes, run, t);
  const auto& s = sc.layout;
  timed_queries(
      t,
      [&] { run.each(sc.n(), [&](int b, int e, PairLists& o) { bvh_query_vertices(s, sc.x, nodes, sc.r, b, e, o); }); },
      [&] {
        run.each(sc.tris(), [&](int b, int e, PairLists& o) { bvh_query_triangles(s, sc.x, nodes, sc.r, b, e, o); });
      },
      [&] {
        run.each(sc.edges(), [&](int b, int e, PairLists& o) { bvh_query_edges(s, sc.x, nodes, sc.r, b, e, o); });
      });
}

// The kernels' lists (8 nearest per primitive) from one walk per group of
// leaves (sc_query_groups), timed as one query (its time stands in the
// per-triangle column).
void leaf_step(const Scene& sc, std::vector<Float4>& nodes, KernelLists& lists, const Runner& run, Timing& t) {
  run.clear();
  bvh_refit_timed(sc, nodes, run, t);
  timed_queries(
      t, [] {},
      [&] {
        run.each_item(bvh_group_count(sc.layout),
                      [&](int b, int e) { bvh_group_lists(sc.layout, sc.xf, nodes, sc.r, b, e, lists); });
      },
      [] {});
}

// One substep of the hash: boxes and cells in parallel, the counting sort
// serial (a parallel one needs per-thread histograms or atomics), three queries.
void hash_step(const Scene& sc, SurfaceHash& h, const Runner& run, Timing& t) {
  const auto& s = sc.layout;
  run.clear();
  auto start = Clock::now();
  run.each_item(sc.n(), [&](int b, int e) {
    hash_boxes(h.vertices, vertex_box_of(sc.x), b, e);
    for (int i = b; i < e; ++i)
      if (!is_surface(s, i)) h.vertices.cells[i] = {{0, 0, 0}, {-1, -1, -1}};
  });
  run.each_item(sc.tris(), [&](int b, int e) { hash_boxes(h.triangles, triangle_box_of(s, sc.x), b, e); });
  run.each_item(sc.edges(), [&](int b, int e) { hash_boxes(h.edges, edge_box_of(s, sc.x), b, e); });
  hash_fill(h.vertices);
  hash_fill(h.triangles);
  hash_fill(h.edges);
  t.build.push_back(ms_since(start));
  timed_queries(
      t, [&] { run.each(sc.n(), [&](int b, int e, PairLists& o) { hash_query_vertices(s, sc.x, h, sc.r, b, e, o); }); },
      [&] {
        run.each(sc.tris(), [&](int b, int e, PairLists& o) { hash_query_triangles(s, sc.x, h, sc.r, b, e, o); });
      },
      [&] { run.each(sc.edges(), [&](int b, int e, PairLists& o) { hash_query_edges(s, sc.x, h, sc.r, b, e, o); }); });
}

// The model of `scene` with the positions of frame `frame` of the result
// file `state` (a run of that scene), or nullopt with a message on stderr (a scene or
// file that cannot be read, a frame it does not hold, another scene's run).
std::optional<model::Model> state_model(const std::string& scene, const std::string& state, int frame) {
  model::Model m;
  std::vector<float> p;
  try {
    m = model::build_model(scene::load_scene_file(scene));
    p = io::read_frame_positions(state, static_cast<std::size_t>(frame));
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return std::nullopt;
  }
  if (p.size() != 3 * m.particles.position.size()) {
    std::fprintf(stderr, "%s: frame %d holds %zu particles, %s has %zu; give the result of a run of that scene\n",
                 state.c_str(), frame, p.size() / 3, scene.c_str(), m.particles.position.size());
    return std::nullopt;
  }
  for (std::size_t i = 0; i < m.particles.position.size(); ++i)
    m.particles.position[i] = Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  return m;
}

// How full the kernels' lists are: per kind (per vertex the triangles, per
// triangle the vertices, per edge the edges), the share of non-empty lists
// and of full ones (ATS_SC_CAPACITY entries: more were within the radius or
// as many), and the mean entries of a non-empty list; then a hash (FNV-1a)
// of all three, to tell whether two builds made the same lists.
std::string list_fill(const KernelLists& l) {
  std::string out;
  std::uint64_t hash = 14695981039346656037ull;
  const char* names[3] = {"vertex", "triangle", "edge"};
  const std::vector<int>* lists[3] = {&l.vt, &l.tv, &l.ee};
  for (int k = 0; k < 3; ++k) {
    for (const int i : *lists[k]) hash = (hash ^ static_cast<std::uint32_t>(i)) * 1099511628211ull;
    const std::size_t count = std::max<std::size_t>(lists[k]->size() / ATS_SC_STRIDE, 1);  // (none: 0 %)
    std::size_t used = 0, full = 0, entries = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const int c = (*lists[k])[i * ATS_SC_STRIDE];
      used += c > 0;
      full += c == ATS_SC_CAPACITY;
      entries += static_cast<std::size_t>(c);
    }
    out += fmt::format("{}{} lists {:.1f} % non-empty, {:.1f} % full, {:.2f} entries a non-empty one", k ? "; " : "",
                       names[k], 100.0 * double(used) / double(count), 100.0 * double(full) / double(count),
                       used ? double(entries) / double(used) : 0.0);
  }
  return out + fmt::format("; hash {:016x}", hash);
}

void uptime(const char* when) {
  std::fflush(stdout);
  std::printf("%s: ", when);
  std::fflush(stdout);
  if (std::system("uptime") != 0) std::printf("(uptime failed)\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Broad phase: refitted BVH against a spatial hash"};
  std::vector<int> sizes{128, 256, 512};
  std::vector<float> cells{1.0f, 2.0f, 4.0f};
  std::vector<int> thread_counts{1, 2};
  int rounds = 5, brute_max = 128, frame = 0;
  bool kernels_only = false;
  std::string scene_path, state_path;
  app.add_option("--sizes", sizes, "cloth grids N x N")->delimiter(',');
  app.add_option("--cells", cells, "hash cell sizes, in query radii")->delimiter(',');
  app.add_option("--threads", thread_counts, "thread counts (1: plain loops; more: TBB)")->delimiter(',');
  app.add_option("--rounds", rounds, "interleaved rounds (the median is printed)");
  app.add_option("--brute-max", brute_max, "largest N checked against brute force");
  auto* scene_opt = app.add_option("--scene", scene_path, "a scene's surfaces instead of the sheet (with --state)");
  app.add_option("--state", state_path, "a result file of that scene, whose --frame positions are used")
      ->needs(scene_opt)
      ->check(CLI::ExistingFile);
  app.add_flag("--kernels-only", kernels_only, "time only the kernels' walk (no BVH pairs, hash or pair check)");
  app.add_option("--frame", frame, "the frame of --state (0: the initial state)")->check(CLI::NonNegativeNumber);
  scene_opt->needs("--state");
  CLI11_PARSE(app, argc, argv);
  if (!scene_path.empty()) sizes = {0};  // one state: the scene's

  uptime("load before");
  bool ok = true;
  std::vector<std::string> rows, parts;
  for (int size : sizes) {
    Scene sc;
    const std::optional<model::Model> read = scene_path.empty() ? std::optional<model::Model>(crumpled_sheet(size))
                                                                : state_model(scene_path, state_path, frame);
    if (!read) return 2;
    const model::Model& m = *read;
    auto start = Clock::now();
    sc.layout = solver::make_self_contact_layout(m);
    const double layout_ms = ms_since(start);
    sc.x = float_positions(m.particles.position);
    sc.xf = float4_positions(sc.x);
    sc.r = sc.layout.query_radius;

    std::vector<Float4> nodes(2 * std::size_t(sc.layout.node_count()));
    KernelLists leaf_lists;
    leaf_lists.resize(sc.layout, sc.x.size());
    std::vector<SurfaceHash> hashes(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) hash_resize(hashes[c], sc.layout, sc.n(), cells[c] * sc.r);

    // Methods: 0 = BVH, 1 = the kernels' one walk per leaf (lists of the 8
    // nearest, not compared pair for pair), 2 + c = hash with cells[c]; per
    // thread count.
    constexpr int kLeaf = 1, kFirstHash = 2;
    const int methods = kFirstHash + static_cast<int>(cells.size());
    std::vector<std::vector<Timing>> timing(thread_counts.size(), std::vector<Timing>(methods));
    std::vector<std::vector<PairLists>> found(thread_counts.size(), std::vector<PairLists>(methods));
    for (int round = 0; round <= rounds; ++round) {  // round 0: warm-up and the pair check
      for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
        tbb::task_arena arena(thread_counts[ti]);
        tbb::enumerable_thread_specific<PairLists> lists;
        PairLists serial;
        const Runner run{thread_counts[ti], &arena, &lists, &serial};
        for (int method = kernels_only ? kLeaf : 0; method < (kernels_only ? kLeaf + 1 : methods); ++method) {
          Timing& t = timing[ti][method];
          if (method == 0) {
            bvh_step(sc, nodes, run, t);
          } else if (method == kLeaf) {
            leaf_step(sc, nodes, leaf_lists, run, t);
          } else {
            hash_step(sc, hashes[method - kFirstHash], run, t);
          }
          if (round == 0) {
            found[ti][method] = run.gathered();
            t.clear();
          }
        }
      }
    }

    const PairLists& bvh = found[0][0];
    for (std::size_t ti = 0; ti < thread_counts.size() && !kernels_only; ++ti) {
      for (int method = 0; method < methods; ++method) {
        if (method == kLeaf) continue;
        if (!same_pairs(found[ti][method], bvh)) {
          std::printf("FAIL: %d x %d, %d threads, method %d: pairs differ from the 1-thread BVH's\n", size, size,
                      thread_counts[ti], method);
          ok = false;
        }
      }
    }
    if (!kernels_only && !transposes_agree(bvh)) {
      std::printf("FAIL: %d x %d: per-triangle pairs are not the per-vertex pairs transposed\n", size, size);
      ok = false;
    }
    std::string brute_note = kernels_only ? "not gathered (--kernels-only)" : "not checked";
    if (!kernels_only && scene_path.empty() && size <= brute_max) {
      tbb::enumerable_thread_specific<PairLists> lists;
      const int count = std::max(sc.n(), sc.edges());
      tbb::parallel_for(tbb::blocked_range<int>(0, count, 64), [&](const tbb::blocked_range<int>& r) {
        brute_force_pairs(sc.layout, sc.x, sc.r, r.begin(), r.end(), lists.local());
      });
      PairLists brute;
      for (const PairLists& l : lists) brute.append(l);
      brute.sort();
      if (same_pairs(brute, bvh)) {
        brute_note = "equal";
      } else {
        std::printf("FAIL: %d x %d: the BVH's pairs differ from the brute force's (%zu vs %zu)\n", size, size,
                    bvh.found(), brute.found());
        ok = false;
        brute_note = "DIFFER";
      }
    }
    const std::string what =
        scene_path.empty() ? fmt::format("{} x {}", size, size) : fmt::format("{} frame {}", state_path, frame);
    std::printf(
        "%s: %d triangles, %d edges, query radius %.4g, layout (BVH build, once) %.1f ms; pairs: %zu vertex-triangle "
        "(found twice), %zu edge-edge (both ways); brute force: %s\n",
        what.c_str(), sc.tris(), sc.edges(), double(sc.r), layout_ms, bvh.vt.size(), bvh.ee.size() / 2,
        brute_note.c_str());
    std::printf("the kernels' lists: %s\n", list_fill(leaf_lists).c_str());
    std::fflush(stdout);

    for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
      const double bvh_total =
          kernels_only ? 0.0 : median(timing[ti][0].build) + median(timing[ti][0].query);  // 0: not run
      for (int method = 0; method < methods; ++method) {
        const Timing& t = timing[ti][method];
        if (t.query.empty()) continue;  // not run (--kernels-only)
        std::vector<double> total(t.build.size());
        for (std::size_t k = 0; k < total.size(); ++k) total[k] = t.build[k] + t.query[k];
        const PairLists& f = found[ti][method];
        const std::string name = method == 0       ? "BVH refit"
                                 : method == kLeaf ? "BVH refit, one walk per group of leaves, 8 nearest (the kernels)"
                                                   : fmt::format("hash, cell {:g} r", cells[method - kFirstHash]);
        const double per_pair = method == kLeaf ? 0.0 : double(f.tested) / double(f.found());
        const double tot = median(total);
        rows.push_back(fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {} |", sc.n(),
                                   thread_counts[ti], name, median(t.build), median(t.query), tot, per_pair,
                                   bvh_total > 0.0 ? fmt::format("{:.2f}", tot / bvh_total) : "–"));
        parts.push_back(fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} |", sc.n(), thread_counts[ti], name,
                                    median(t.part[0]), median(t.part[1]), median(t.part[2])));
      }
    }
  }
  std::printf(
      "\n| vertices | threads | broad phase | build/refit ms | query ms | total ms/substep | tested / pair "
      "found | total / BVH total |\n|---:|---:|---|---:|---:|---:|---:|---:|\n");
  for (const auto& row : rows) std::printf("%s\n", row.c_str());
  std::printf(
      "\nThe query ms per kind (medians):\n\n| vertices | threads | broad phase | per vertex the triangles | "
      "per triangle the vertices | per edge the edges |\n|---:|---:|---|---:|---:|---:|\n");
  for (const auto& row : parts) std::printf("%s\n", row.c_str());
  uptime("load after");
  if (!ok) std::printf("FAIL: the broad phases disagree (see above)\n");
  return ok ? 0 : 1;
}
