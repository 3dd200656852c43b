#include "solver/explicit/explicit_reference.hpp"

#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#define ats_float4 ::atssim::solver::Float4
#include "common/vertex_force.h"
#include "util/error.hpp"

namespace atssim::solver::explicit_rk {

struct ExplicitReference::Arena {
  explicit Arena(int threads) : arena(threads) {}
  tbb::task_arena arena;
};

ExplicitReference::ExplicitReference(SimLayout layout, ExplicitSettings settings, int threads)
    : layout_(std::move(layout)),
      settings_(settings),
      vertices_(vertex::make_vertex_layout(layout_)),
      xs_(layout_.x),
      vs_(layout_.v),
      accel_(layout_.x.size()),
      sum_x_(layout_.x.size()),
      sum_v_(layout_.x.size()) {
  if (threads < 1) throw input_error("the explicit reference needs threads >= 1, got " + std::to_string(threads));
  if (threads > 1) arena_ = std::make_unique<Arena>(threads);
}

ExplicitReference::ExplicitReference(ExplicitReference&&) noexcept = default;
ExplicitReference& ExplicitReference::operator=(ExplicitReference&&) noexcept = default;
ExplicitReference::~ExplicitReference() = default;

template <class Body>
void ExplicitReference::sweep(const Body& body) {
  const int n = static_cast<int>(layout_.x.size());
  if (!arena_) {
    for (int i = 0; i < n; ++i) body(i);
    return;
  }
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 256), [&](const tbb::blocked_range<int>& r) {
      for (int i = r.begin(); i < r.end(); ++i) body(i);
    });
  });
}

void ExplicitReference::forces(const std::vector<Float4>& xs, const std::vector<Float4>& vs) {
  const ats_vec3 g = ats_v3(layout_.gravity.x, layout_.gravity.y, layout_.gravity.z);
  sweep([&](int i) {
    const ats_vec3 a =
        particle_acceleration(i, xs.data(), vs.data(), vertices_.adjacency_offsets.data(), vertices_.adjacency.data(),
                              layout_.stretch.data(), layout_.bend.data(), layout_.tets.data(), g, layout_.air_drag);
    accel_[i] = {a.x, a.y, a.z, 0.0f};
  });
}

void ExplicitReference::substep() {
  const float h = static_cast<float>(settings_.substep_dt);
  std::vector<Float4>& x = layout_.x;
  std::vector<Float4>& v = layout_.v;
  if (settings_.integrator == Integrator::semi_euler) {
    forces(x, v);
    sweep([&](int i) {
      if (x[i].w == 0.0f) {
        v[i] = {};
        return;
      }
      v[i] = {v[i].x + h * accel_[i].x, v[i].y + h * accel_[i].y, v[i].z + h * accel_[i].z, 0.0f};
      x[i] = {x[i].x + h * v[i].x, x[i].y + h * v[i].y, x[i].z + h * v[i].z, x[i].w};
    });
    return;
  }
  // Explicit Runge-Kutta: midpoint (c = 1/2; weights 0, 1) or RK4 (c = 1/2,
  // 1/2, 1; weights 1, 2, 2, 1 over 6), as the plan's stages.
  const bool rk4 = settings_.integrator == Integrator::rk4;
  const float c[3] = {0.5f, 0.5f, 1.0f};
  const float w[4] = {rk4 ? 1.0f : 0.0f, rk4 ? 2.0f : 1.0f, 2.0f, 1.0f};
  const int stages = rk4 ? 4 : 2;
  const float h_sum = rk4 ? h / 6.0f : h;
  for (int s = 0; s < stages; ++s) {
    const bool first = s == 0;
    forces(first ? x : xs_, first ? v : vs_);
    if (s + 1 < stages) {
      sweep([&](int i) {
        const Float4 kx = first ? v[i] : vs_[i], kv = accel_[i];
        const Float4 sx = first ? Float4{} : sum_x_[i], sv = first ? Float4{} : sum_v_[i];
        sum_x_[i] = {sx.x + w[s] * kx.x, sx.y + w[s] * kx.y, sx.z + w[s] * kx.z, 0.0f};
        sum_v_[i] = {sv.x + w[s] * kv.x, sv.y + w[s] * kv.y, sv.z + w[s] * kv.z, 0.0f};
        const float ch = c[s] * h;
        xs_[i] = {x[i].x + ch * kx.x, x[i].y + ch * kx.y, x[i].z + ch * kx.z, x[i].w};
        vs_[i] = {v[i].x + ch * kv.x, v[i].y + ch * kv.y, v[i].z + ch * kv.z, 0.0f};
      });
    } else {
      sweep([&](int i) {
        if (x[i].w == 0.0f) {
          v[i] = {};
          return;
        }
        const Float4 kx = vs_[i], kv = accel_[i], sx = sum_x_[i], sv = sum_v_[i];
        x[i] = {x[i].x + h_sum * (sx.x + w[s] * kx.x), x[i].y + h_sum * (sx.y + w[s] * kx.y),
                x[i].z + h_sum * (sx.z + w[s] * kx.z), x[i].w};
        v[i] = {v[i].x + h_sum * (sv.x + w[s] * kv.x), v[i].y + h_sum * (sv.y + w[s] * kv.y),
                v[i].z + h_sum * (sv.z + w[s] * kv.z), 0.0f};
      });
    }
  }
}

}  // namespace atssim::solver::explicit_rk
