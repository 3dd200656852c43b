#pragma once
// Divergence detection relative to the scene, not to a fixed distance: a
// frame blew up when a position is not finite or a particle moved further
// in one frame than the scene allows — ten times its size per substep plus
// ten times the distance the fastest initial velocity plus gravity since the
// start could carry it. A scene placed far from the origin is fine; a
// particle that jumps by the scene's size in a substep is not.
#include <optional>
#include <span>
#include <string>

namespace atssim::app {

struct BlowUpBounds {
  double scene_size = 1.0;  // diagonal of the initial bounding box (m), at least 1 mm
  double speed0 = 0.0;      // fastest initial speed (m/s)
  double gravity = 0.0;     // |g| (m/s²)
  double substep_dt = 0.0;  // s
  int substeps = 1;         // per frame
};

// Bounds of a run from its initial positions and velocities (xyz triplets).
BlowUpBounds blow_up_bounds(std::span<const float> xyz, std::span<const float> velocities_xyz, double gravity,
                            double frame_dt, int substeps);

// The largest distance a particle may move in the frame that ends at time `t`.
double max_frame_displacement(const BlowUpBounds& b, double t);

// What is wrong with frame `frame` (ending at time t) given the previous
// recorded positions `before` (`frames_between` frames earlier), or nothing.
std::optional<std::string> find_blow_up(std::span<const float> before, std::span<const float> after,
                                        const BlowUpBounds& b, double t, int frames_between);

}  // namespace atssim::app
