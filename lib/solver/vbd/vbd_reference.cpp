#include "solver/vbd/vbd_reference.hpp"

#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "solver/energy/finite_stiffness.hpp"
#include "util/error.hpp"

// The kernels' particle type is float4; here the layout's own (same fields).
#define ats_float4 ::atssim::solver::Float4
#include "common/particle_step.h"
#include "common/vertex_solve.h"
#include "common/vertex_system.h"
#include "common/vertex_system_lanes.h"

namespace atssim::solver::vbd {

struct VbdReference::Arena {
  explicit Arena(int threads) : arena(threads) {}
  tbb::task_arena arena;
};

VbdReference::VbdReference(SimLayout layout, double substep_dt, int iterations, int threads, bool lanes)
    : layout_(std::move(layout)),
      vertices_(vertex::make_vertex_layout(layout_)),
      lanes_(lanes ? vertex::color_lanes(vertices_.colors) : vertex::ColorLanes{}),
      substep_dt_(substep_dt),
      iterations_(iterations),
      x_prev_(layout_.x),
      x_tilde_(layout_.x) {
  energy::require_finite_stiffness(layout_);
  if (threads < 1) throw input_error("the VBD reference needs threads >= 1, got " + std::to_string(threads));
  if (threads > 1) arena_ = std::make_unique<Arena>(threads);
  // As damping_args: 1/h where a spring is damped, else 0 (looked up once, not per color).
  damping_inv_h_ = has_spring_damping(layout_) ? static_cast<float>(1.0 / substep_dt_) : 0.0f;
}

VbdReference::VbdReference(VbdReference&&) noexcept = default;
VbdReference& VbdReference::operator=(VbdReference&&) noexcept = default;
VbdReference::~VbdReference() = default;

// With threads > 1 substep() is already inside the arena (entered once per
// substep, not once per color): each sweep is one plain parallel_for.
template <class Body>
void VbdReference::sweep(int first, int last, const Body& body) {
  if (!arena_) {
    for (int i = first; i < last; ++i) body(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(first, last), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(), e = r.end(); i < e; ++i) body(i);
  });
}

void VbdReference::substep() {
  if (arena_) {
    arena_->arena.execute([&] { substep_here(); });
  } else {
    substep_here();
  }
}

// The task order of make_vbd_plan (lib/solver/vbd/vbd_plan.cpp).
void VbdReference::substep_here() {
  predict();
  for (int it = 0; it < iterations_; ++it) {
    for (int c = 0; c < vertices_.colors.count(); ++c) {
      if (lanes_.offsets.empty()) {
        solve_color(c);
      } else {
        solve_color_lanes(c);
      }
    }
    if (layout_.has_ground) project_ground();
  }
  update_velocity();
}

// particles_predict (kernels/common/particle_steps.cl).
void VbdReference::predict() {
  const float dt = static_cast<float>(substep_dt_);
  const float damp = velocity_damping(layout_, substep_dt_);
  const Float4 g = layout_.gravity;
  sweep(0, static_cast<int>(layout_.x.size()), [&](int i) {
    x_prev_[i] = layout_.x[i];
    const ats_particle_state s = ats_predicted(layout_.x[i], layout_.v[i], dt, g.x, g.y, g.z, damp);
    layout_.x[i] = s.x;
    layout_.v[i] = s.v;
    x_tilde_[i] = s.x;
  });
}

namespace {

// vbd_step (kernels/vbd/vbd.cl) without contact: spring damping, the 3x3
// solve, the ground.
void step_vertex(SimLayout& layout, int i, vertex_system s, const Float4* x_prev, float inv_h,
                 const vertex::VertexLayout& vertices) {
  const Float4* x = layout.x.data();
  s = add_spring_damping(s, i, x, x_prev, inv_h, vertices.adjacency_offsets.data(), vertices.adjacency.data(),
                         layout.stretch.data());
  const ats_solve3 d = ats_m3_solve(s.h, s.f);
  if (!d.ok) return;
  Float4& p = layout.x[i];
  ats_vec3 step = d.x;
  if (layout.has_ground && p.y + step.y < layout.ground_y) {
    step = ats_vertex_step_above_ground(s.h, s.f, step, p.y, layout.ground_y);
  }
  p = {p.x + step.x, p.y + step.y, p.z + step.z, p.w};
}

}  // namespace

// vbd_solve (kernels/vbd/vbd.cl): one 3x3 Newton step per vertex of the
// color, its neighbours (other colors) held fixed.
void VbdReference::solve_color(int color) {
  const double hi = inertia_dt(layout_, substep_dt_);
  const float inv_h2 = static_cast<float>(1.0 / (hi * hi));
  const float inv_h = damping_inv_h_;
  const Float4* x = layout_.x.data();
  const int* order = vertices_.colors.order.data();
  sweep(vertices_.colors.offsets[color], vertices_.colors.offsets[color + 1], [&](int k) {
    const int i = order[k];
    step_vertex(layout_, i,
                gather_vertex_system(i, x, x_tilde_.data(), inv_h2, vertices_.adjacency_offsets.data(),
                                     vertices_.adjacency.data(), layout_.stretch.data(), layout_.bend.data(),
                                     layout_.tets.data()),
                x_prev_.data(), inv_h, vertices_);
  });
}

// vbd_solve_lanes (kernels/vbd/vbd.cl): the color's batches of 8 vertices,
// each gathered as 8 float lanes, then stepped one after another.
void VbdReference::solve_color_lanes(int color) {
  const double hi = inertia_dt(layout_, substep_dt_);
  const float inv_h2 = static_cast<float>(1.0 / (hi * hi));
  const float inv_h = damping_inv_h_;
  const Float4* x = layout_.x.data();
  sweep(lanes_.offsets[color], lanes_.offsets[color + 1], [&](int b) {
    const int* v = lanes_.order.data() + vertex::kLaneWidth * b;
    if (inv_h == 0.0f) {  // no damping: the solve as lanes too, as the kernel's
      ats_f8 acc[12];
      gather_vertex_system8_lanes(v, x, x_tilde_.data(), inv_h2, vertices_.adjacency_offsets.data(),
                                  vertices_.adjacency.data(), layout_.stretch.data(), layout_.bend.data(),
                                  layout_.tets.data(), acc);
      ats_vbd_step8(v, acc, layout_.x.data(), layout_.has_ground ? 1 : 0, layout_.ground_y);
      return;
    }
    vertex_system s[vertex::kLaneWidth];
    gather_vertex_system8(v, x, x_tilde_.data(), inv_h2, vertices_.adjacency_offsets.data(), vertices_.adjacency.data(),
                          layout_.stretch.data(), layout_.bend.data(), layout_.tets.data(), s);
    for (int l = 0; l < vertex::kLaneWidth; ++l) {
      if (v[l] >= 0) step_vertex(layout_, v[l], s[l], x_prev_.data(), inv_h, vertices_);
    }
  });
}

// particles_ground (kernels/common/particle_steps.cl).
void VbdReference::project_ground() {
  sweep(0, static_cast<int>(layout_.x.size()),
        [&](int i) { layout_.x[i] = ats_above_ground(layout_.x[i], layout_.ground_y); });
}

// particles_update_velocity (kernels/common/particle_steps.cl), with the
// plan's 1/h rounded from double.
void VbdReference::update_velocity() {
  const float inv_dt = static_cast<float>(1.0 / substep_dt_);
  sweep(0, static_cast<int>(layout_.x.size()),
        [&](int i) { layout_.v[i] = ats_velocity_update(layout_.x[i], x_prev_[i], inv_dt); });
}

}  // namespace atssim::solver::vbd
