#include "solver/xpbd/xpbd_reference.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "util/error.hpp"

// The kernels' particle type is float4; here the layout's own (same fields).
#define ats_float4 ::atssim::solver::Float4
#include "common/particle_step.h"
#include "common/xpbd_bending.h"
#include "common/xpbd_distance.h"
#include "common/xpbd_tet.h"

namespace atssim::solver::xpbd {

namespace {
ats_vec3 xyz(const Float4& p) { return ats_v3(p.x, p.y, p.z); }
ats_mat3 dm_inv_of(const ats_tet_c& t) {
  ats_mat3 m;
  for (int r = 0; r < 3; ++r) m.r[r] = ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
  return m;
}
// Pinned particles are shared inside a color block (they create no
// conflict, graph/color_blocks.hpp) and get no correction: they are not
// written, so that two threads never write one particle.
void add_xyz(Float4& p, ats_vec3 d) {
  if (p.w == 0.0f) return;
  p.x += d.x;
  p.y += d.y;
  p.z += d.z;
}
}  // namespace

struct XpbdReference::Arena {
  explicit Arena(int threads) : arena(threads) {}
  tbb::task_arena arena;
};

XpbdReference::XpbdReference(SimLayout layout, XpbdSettings settings, int threads)
    : layout_(std::move(layout)),
      settings_(settings),
      x_prev_(layout_.x),
      stretch_lambda_(layout_.stretch.size(), 0.0f),
      bend_lambda_(layout_.bend.size() * 3, 0.0f),
      tet_lambda_(layout_.tets.size() * ATS_TET_LAMBDA_STRIDE, 0.0f),
      // As xpbd_stretch with its plan's 1/h (0 without damped springs).
      inv_h_(has_spring_damping(layout_) ? 1.0f / static_cast<float>(settings_.substep_dt) : 0.0f) {
  if (threads < 1) throw input_error("the XPBD reference needs threads >= 1, got " + std::to_string(threads));
  if (threads > 1) arena_ = std::make_unique<Arena>(threads);
}

XpbdReference::XpbdReference(XpbdReference&&) noexcept = default;
XpbdReference& XpbdReference::operator=(XpbdReference&&) noexcept = default;
XpbdReference::~XpbdReference() = default;

// The constraint bodies are inlined into the loops that call them: GCC keeps
// a large lambda called from two places (the serial loop and the
// parallel_for's) out of line, one call per constraint, which made this
// loop 1.6-1.8x slower than the same body written inline (bench_native
// --loop plain, docs/benchmarks.md).
#if defined(__GNUC__)
#define ATS_INLINE_BODY __attribute__((always_inline))
#else
#define ATS_INLINE_BODY
#endif

// With threads > 1 substep() is already inside the arena (entered once per
// substep, not once per block): each sweep is one plain parallel_for.
template <class Body>
void XpbdReference::sweep(int first, int last, const Body& body) {
  if (!arena_) {
    for (int i = first; i < last; ++i) body(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(first, last), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(), e = r.end(); i < e; ++i) body(i);
  });
}

void XpbdReference::substep() {
  if (arena_) {
    arena_->arena.execute([&] { substep_here(); });
  } else {
    substep_here();
  }
}

void XpbdReference::substep_here() {
  predict();
  for (int it = 0; it < settings_.iterations; ++it) {
    solve_stretch(it == 0);
    solve_bend(it == 0);
    solve_tets(it == 0);
    if (layout_.has_ground) project_ground();
  }
  update_velocity();
}

// xpbd_predict (kernels/xpbd/xpbd.cl), with make_xpbd_plan's arguments.
void XpbdReference::predict() {
  const float dt = static_cast<float>(settings_.substep_dt);
  const float damp = velocity_damping(layout_, settings_.substep_dt);
  const Float4 g = layout_.gravity;
  sweep(0, static_cast<int>(layout_.x.size()), [&](int i) {
    x_prev_[i] = layout_.x[i];
    const ats_particle_state s = ats_predicted(layout_.x[i], layout_.v[i], dt, g.x, g.y, g.z, damp);
    layout_.x[i] = s.x;
    layout_.v[i] = s.v;
  });
}

// Blocks in order; inside a block no two constraints share a movable
// particle, so any order (or thread) inside a block gives the same result.
void XpbdReference::solve_stretch(bool reset) {
  const float dt = static_cast<float>(inertia_dt(layout_, settings_.substep_dt));
  const float inv_h = inv_h_;
  // Raw pointers, captured by value: through `this` the compiler reloads the
  // arrays after every store (a float store may alias them).
  Float4* x = layout_.x.data();
  const Float4* x0 = x_prev_.data();
  const ats_distance_c* con = layout_.stretch.data();
  float* lambda = stretch_lambda_.data();
  for (std::size_t b = 0; b + 1 < layout_.stretch_blocks.size(); ++b) {
    sweep(layout_.stretch_blocks[b], layout_.stretch_blocks[b + 1], [=](int i) ATS_INLINE_BODY {
      const ats_distance_c c = con[i];
      Float4& pa = x[c.a];
      Float4& pb = x[c.b];
      const float l = reset ? 0.0f : lambda[i];
      const float gamma = c.damping * inv_h;
      const ats_distance_step s = gamma > 0.0f
                                      ? ats_xpbd_distance_damped(xyz(pa), pa.w, xyz(pb), pb.w, c.rest, c.compliance, l,
                                                                 dt, xyz(x0[c.a]), xyz(x0[c.b]), gamma)
                                      : ats_xpbd_distance(xyz(pa), pa.w, xyz(pb), pb.w, c.rest, c.compliance, l, dt);
      lambda[i] = l + s.dlambda;
      add_xyz(pa, s.dxa);
      add_xyz(pb, s.dxb);
    });
  }
}

void XpbdReference::solve_bend(bool reset) {
  const float dt = static_cast<float>(inertia_dt(layout_, settings_.substep_dt));
  Float4* x = layout_.x.data();
  const ats_bend_c* con = layout_.bend.data();
  float* lambda = bend_lambda_.data();
  for (std::size_t b = 0; b + 1 < layout_.bend_blocks.size(); ++b) {
    sweep(layout_.bend_blocks[b], layout_.bend_blocks[b + 1], [=](int i) ATS_INLINE_BODY {
      const ats_bend_c& c = con[i];
      ats_vec3 p[4];
      float w[4];
      for (int j = 0; j < 4; ++j) {
        const Float4 q = x[c.v[j]];
        p[j] = xyz(q);
        w[j] = q.w;
      }
      float* lam = lambda + 3 * i;
      const ats_vec3 l = reset ? ats_v3(0, 0, 0) : ats_v3(lam[0], lam[1], lam[2]);
      const ats_bend_step s = ats_xpbd_bend_element(p, w, &c, l, dt);
      lam[0] = l.x + s.dlambda.x;
      lam[1] = l.y + s.dlambda.y;
      lam[2] = l.z + s.dlambda.z;
      for (int j = 0; j < 4; ++j) add_xyz(x[c.v[j]], s.dx[j]);
    });
  }
}

void XpbdReference::solve_tets(bool reset) {
  const float dt = static_cast<float>(inertia_dt(layout_, settings_.substep_dt));
  for (std::size_t b = 0; b + 1 < layout_.tet_blocks.size(); ++b) {
    sweep(layout_.tet_blocks[b], layout_.tet_blocks[b + 1], [&](int i) ATS_INLINE_BODY {
      const ats_tet_c& t = layout_.tets[i];
      ats_vec3 p[4];
      float w[4];
      for (int j = 0; j < 4; ++j) {
        p[j] = xyz(layout_.x[t.v[j]]);
        w[j] = layout_.x[t.v[j]].w;
      }
      const ats_mat3 dm_inv = dm_inv_of(t);
      float* lam = &tet_lambda_[ATS_TET_LAMBDA_STRIDE * i];
      if (reset) std::fill(lam, lam + ATS_TET_LAMBDA_STRIDE, 0.0f);
      ats_xpbd_tet(p, w, dm_inv, t.volume, t.mu, t.lambda, lam, dt);
      for (int j = 0; j < 4; ++j) {
        Float4& q = layout_.x[t.v[j]];
        if (q.w == 0.0f) continue;  // pinned: shared inside a block, never moved (see add_xyz)
        q.x = p[j].x;
        q.y = p[j].y;
        q.z = p[j].z;
      }
    });
  }
}

// particles_ground (kernels/common/particle_steps.cl).
void XpbdReference::project_ground() {
  sweep(0, static_cast<int>(layout_.x.size()),
        [&](int i) { layout_.x[i] = ats_above_ground(layout_.x[i], layout_.ground_y); });
}

// particles_update_velocity, with make_xpbd_plan's 1/h (rounded in float).
void XpbdReference::update_velocity() {
  const float inv_dt = 1.0f / static_cast<float>(settings_.substep_dt);
  sweep(0, static_cast<int>(layout_.x.size()),
        [&](int i) { layout_.v[i] = ats_velocity_update(layout_.x[i], x_prev_[i], inv_dt); });
}

double XpbdReference::residual_rms() const {
  const float dt = static_cast<float>(inertia_dt(layout_, settings_.substep_dt));
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < layout_.stretch.size(); ++i) {
    const ats_distance_c& c = layout_.stretch[i];
    const double r = ats_xpbd_distance_residual(xyz(layout_.x[c.a]), xyz(layout_.x[c.b]), c.rest, c.compliance,
                                                stretch_lambda_[i], dt);
    sum += r * r;
    ++count;
  }
  for (std::size_t i = 0; i < layout_.bend.size(); ++i) {
    const ats_bend_c& c = layout_.bend[i];
    ats_vec3 p[4];
    for (int j = 0; j < 4; ++j) p[j] = xyz(layout_.x[c.v[j]]);
    const ats_vec3 l = ats_v3(bend_lambda_[3 * i], bend_lambda_[3 * i + 1], bend_lambda_[3 * i + 2]);
    const ats_vec3 res = ats_xpbd_bend_residual(p, &c, l, dt);
    const double r[3] = {res.x, res.y, res.z};
    for (double v : r) sum += v * v;
    count += 3;
  }
  for (std::size_t i = 0; i < layout_.tets.size(); ++i) {
    const ats_tet_c& t = layout_.tets[i];
    ats_vec3 p[4];
    for (int j = 0; j < 4; ++j) p[j] = xyz(layout_.x[t.v[j]]);
    for (int c = 0; c < ATS_TET_STRAIN_CONSTRAINTS; ++c) {
      const double r = ats_xpbd_tet_residual(p, dm_inv_of(t), t.volume, t.mu, t.lambda,
                                             tet_lambda_[ATS_TET_LAMBDA_STRIDE * i + c], dt, c);
      sum += r * r;
      ++count;
    }
  }
  return count == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(count));
}

}  // namespace atssim::solver::xpbd
