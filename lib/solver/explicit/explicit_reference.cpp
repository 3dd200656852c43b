#include "solver/explicit/explicit_reference.hpp"

#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#define ats_float4 ::atssim::solver::Float4
#include "common/particle_step.h"
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
      const ats_particle_state s = ats_semi_euler(x[i], v[i], accel_[i], h);
      x[i] = s.x;
      v[i] = s.v;
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
        const ats_rk_stage_state r =
            ats_rk_stage(x[i], v[i], first ? v[i] : vs_[i], accel_[i], first ? Float4{} : sum_x_[i],
                         first ? Float4{} : sum_v_[i], w[s], c[s] * h);
        sum_x_[i] = r.sum_x;
        sum_v_[i] = r.sum_v;
        xs_[i] = r.xs;
        vs_[i] = r.vs;
      });
    } else {
      sweep([&](int i) {
        const ats_particle_state r = ats_rk_finish(x[i], v[i], vs_[i], accel_[i], sum_x_[i], sum_v_[i], w[s], h_sum);
        x[i] = r.x;
        v[i] = r.v;
      });
    }
  }
}

}  // namespace atssim::solver::explicit_rk
