#pragma once
// The sceptic's baseline for bench_native (docs/benchmarks.md, "Native
// loops"): the XPBD substep written the plain way, apart from the project's
// host reference (solver/xpbd/xpbd_reference) — the layout's arrays copied
// into local vectors, raw pointers captured by the loop bodies, the
// kernels/common math, one tbb::parallel_for per color block (the caller
// enters its task arena once, around all the frames), plain loops on one
// thread. The same operations in the same order as the reference, so both
// end on the same positions (bench_native prints the checksum).
// (bench/plain_xpbd_batches.hpp: the same over the batches ordering.)
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/xpbd_bending.h"
#include "common/xpbd_distance.h"
#include "solver/layout/sim_layout.hpp"
#include "util/error.hpp"

namespace atssim::bench {

// body(i) for i in [first, last): a plain loop, or one tbb::parallel_for.
template <class Body>
inline void plain_range(bool parallel, int first, int last, const Body& body) {
  if (!parallel) {
    for (int i = first; i < last; ++i) body(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(first, last), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(), e = r.end(); i < e; ++i) body(i);
  });
}

// The parts of the XPBD substep every loop here shares: predict and the
// velocity update over the particles (as kernels/common/particle_steps.cl).
class PlainParticles {
 public:
  PlainParticles(const solver::SimLayout& layout, double h)
      : x_(layout.x),
        v_(layout.v),
        x_prev_(layout.x),
        gravity_(layout.gravity),
        dt_(static_cast<float>(h)),
        inv_dt_(1.0f / static_cast<float>(h)),
        damp_(solver::velocity_damping(layout, h)),
        has_ground_(layout.has_ground),
        ground_y_(layout.ground_y) {}

  const std::vector<solver::Float4>& positions() const { return x_; }

 protected:
  void predict(bool parallel) {
    solver::Float4* x = x_.data();
    solver::Float4* v = v_.data();
    solver::Float4* x0 = x_prev_.data();
    const solver::Float4 g = gravity_;
    const float dt = dt_, damp = damp_;
    plain_range(parallel, 0, static_cast<int>(x_.size()), [=](int i) {
      solver::Float4 p = x[i];
      x0[i] = p;
      if (p.w == 0.0f) {
        v[i] = {};
        return;
      }
      solver::Float4 u = v[i];
      u.x = (u.x + dt * g.x) * damp;
      u.y = (u.y + dt * g.y) * damp;
      u.z = (u.z + dt * g.z) * damp;
      v[i] = u;
      x[i] = {p.x + dt * u.x, p.y + dt * u.y, p.z + dt * u.z, p.w};
    });
  }
  void ground(bool parallel) {
    if (!has_ground_) return;
    solver::Float4* x = x_.data();
    const float y = ground_y_;
    plain_range(parallel, 0, static_cast<int>(x_.size()), [=](int i) {
      if (x[i].w > 0.0f && x[i].y < y) x[i].y = y;
    });
  }
  void update_velocity(bool parallel) {
    const solver::Float4* x = x_.data();
    const solver::Float4* x0 = x_prev_.data();
    solver::Float4* v = v_.data();
    const float inv = inv_dt_;
    plain_range(parallel, 0, static_cast<int>(x_.size()), [=](int i) {
      v[i] = {(x[i].x - x0[i].x) * inv, (x[i].y - x0[i].y) * inv, (x[i].z - x0[i].z) * inv, 0.0f};
    });
  }

  std::vector<solver::Float4> x_, v_, x_prev_;
  solver::Float4 gravity_;
  float dt_, inv_dt_, damp_;
  bool has_ground_;
  float ground_y_;
};

// The per-color loop: threads > 1 runs each color block as a parallel_for.
class PlainXpbd : public PlainParticles {
 public:
  PlainXpbd(const solver::SimLayout& layout, double h, int iterations, bool parallel)
      : PlainParticles(layout, h),
        stretch_(layout.stretch),
        stretch_blocks_(layout.stretch_blocks),
        bend_(layout.bend),
        bend_blocks_(layout.bend_blocks),
        stretch_lambda_(layout.stretch.size()),
        bend_lambda_(layout.bend.size() * 3),
        iterations_(iterations),
        parallel_(parallel),
        inertia_dt_(static_cast<float>(solver::inertia_dt(layout, h))),
        inv_h_(solver::has_spring_damping(layout) ? 1.0f / static_cast<float>(h) : 0.0f) {
    if (!layout.tets.empty()) throw input_error("bench_native --loop plain: cloth only (the scene has tetrahedra)");
  }

  void substep() {
    predict(parallel_);
    for (int it = 0; it < iterations_; ++it) {
      const bool reset = it == 0;
      for (std::size_t b = 0; b + 1 < stretch_blocks_.size(); ++b)
        stretch(stretch_blocks_[b], stretch_blocks_[b + 1], reset);
      for (std::size_t b = 0; b + 1 < bend_blocks_.size(); ++b) bend(bend_blocks_[b], bend_blocks_[b + 1], reset);
      ground(parallel_);
    }
    update_velocity(parallel_);
  }

 private:
  static ats_vec3 xyz(const solver::Float4& p) { return ats_v3(p.x, p.y, p.z); }
  static void add(solver::Float4& p, ats_vec3 d) {
    if (p.w == 0.0f) return;  // pinned: shared inside a block, never written
    p.x += d.x;
    p.y += d.y;
    p.z += d.z;
  }

  void stretch(int first, int last, bool reset) {
    solver::Float4* x = x_.data();
    const solver::Float4* x0 = x_prev_.data();
    const ats_distance_c* con = stretch_.data();
    float* lambda = stretch_lambda_.data();
    const float dt = inertia_dt_, inv_h = inv_h_;
    plain_range(parallel_, first, last, [=](int i) {
      const ats_distance_c c = con[i];
      solver::Float4& pa = x[c.a];
      solver::Float4& pb = x[c.b];
      const float l = reset ? 0.0f : lambda[i];
      const float gamma = c.damping * inv_h;
      const ats_distance_step s = gamma > 0.0f
                                      ? ats_xpbd_distance_damped(xyz(pa), pa.w, xyz(pb), pb.w, c.rest, c.compliance, l,
                                                                 dt, xyz(x0[c.a]), xyz(x0[c.b]), gamma)
                                      : ats_xpbd_distance(xyz(pa), pa.w, xyz(pb), pb.w, c.rest, c.compliance, l, dt);
      lambda[i] = l + s.dlambda;
      add(pa, s.dxa);
      add(pb, s.dxb);
    });
  }

  void bend(int first, int last, bool reset) {
    solver::Float4* x = x_.data();
    const ats_bend_c* con = bend_.data();
    float* lambda = bend_lambda_.data();
    const float dt = inertia_dt_;
    plain_range(parallel_, first, last, [=](int i) {
      const ats_bend_c& c = con[i];
      ats_vec3 p[4];
      float w[4];
      for (int j = 0; j < 4; ++j) {
        const solver::Float4 q = x[c.v[j]];
        p[j] = xyz(q);
        w[j] = q.w;
      }
      float* lam = lambda + 3 * i;
      const ats_vec3 l = reset ? ats_v3(0, 0, 0) : ats_v3(lam[0], lam[1], lam[2]);
      const ats_bend_step s = ats_xpbd_bend_element(p, w, &c, l, dt);
      lam[0] = l.x + s.dlambda.x;
      lam[1] = l.y + s.dlambda.y;
      lam[2] = l.z + s.dlambda.z;
      for (int j = 0; j < 4; ++j) add(x[c.v[j]], s.dx[j]);
    });
  }

  std::vector<ats_distance_c> stretch_;
  std::vector<int> stretch_blocks_;
  std::vector<ats_bend_c> bend_;
  std::vector<int> bend_blocks_;
  std::vector<float> stretch_lambda_, bend_lambda_;
  int iterations_;
  bool parallel_;
  float inertia_dt_, inv_h_;
};

}  // namespace atssim::bench
