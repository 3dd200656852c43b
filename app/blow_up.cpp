#include "app/blow_up.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace atssim::app {

BlowUpBounds blow_up_bounds(std::span<const float> xyz, std::span<const float> velocities_xyz, double gravity,
                            double frame_dt, int substeps) {
  BlowUpBounds b;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], double(xyz[i + k]));
      hi[k] = std::max(hi[k], double(xyz[i + k]));
    }
  }
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) d2 += hi[k] > lo[k] ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0.0;
  b.scene_size = std::max(std::sqrt(d2), 1e-3);
  for (std::size_t i = 0; i + 2 < velocities_xyz.size(); i += 3) {
    const double v = std::hypot(velocities_xyz[i], velocities_xyz[i + 1], velocities_xyz[i + 2]);
    if (std::isfinite(v)) b.speed0 = std::max(b.speed0, v);
  }
  b.gravity = gravity;
  b.substeps = std::max(substeps, 1);
  b.substep_dt = frame_dt / b.substeps;
  return b;
}

double max_frame_displacement(const BlowUpBounds& b, double t) {
  const double per_substep = 10.0 * (b.scene_size + (b.speed0 + b.gravity * t) * b.substep_dt);
  return per_substep * b.substeps;
}

std::optional<std::string> find_blow_up(std::span<const float> before, std::span<const float> after,
                                        const BlowUpBounds& b, double t, int frames_between) {
  const double allowed = max_frame_displacement(b, t) * std::max(frames_between, 1);
  for (std::size_t i = 0; i + 2 < after.size(); i += 3) {
    if (!std::isfinite(after[i]) || !std::isfinite(after[i + 1]) || !std::isfinite(after[i + 2])) {
      return fmt::format("particle {} is at a non-finite position", i / 3);
    }
  }
  if (before.size() != after.size()) return std::nullopt;
  for (std::size_t i = 0; i + 2 < after.size(); i += 3) {
    const double moved = std::hypot(double(after[i]) - before[i], double(after[i + 1]) - before[i + 1],
                                    double(after[i + 2]) - before[i + 2]);
    if (moved > allowed) {
      return fmt::format(
          "particle {} moved {:.3g} m in {} frame(s), more than the {:.3g} m the scene's size "
          "({:.3g} m), gravity and time step allow",
          i / 3, moved, std::max(frames_between, 1), allowed, b.scene_size);
    }
  }
  return std::nullopt;
}

}  // namespace atssim::app
