#pragma once
// Blow-up by energy: a frame blew up when its kinetic plus elastic energy
// grew by more than a factor (simulation.energy_growth_limit, default 1000)
// over the frame before, beyond the work gravity did in the frame. The
// displacement check (app/blow_up.hpp) is relative to the scene's size, so
// a large scene torn apart within that size passes it; the energy does not.
//
//   E = sum_free 1/2 m |v|^2 + sum_elements Psi_e(x)
//   blow-up when E_after - max(W_g, 0) > factor * max(E_before, E_scale),
//   W_g = sum_free m g . (x_after - x_before),
//   E_scale = M (max(|g|, 9.81 m/s^2) L + 1/2 v0^2)
//
// with M the free mass, L the diagonal of the initial bounding box and v0
// the fastest initial speed: the energy the scene could hold without
// anything going wrong, so that a scene at rest may start moving.
// Colliders that move and contact forces add work that is not counted;
// E_scale and the factor leave room for them. Constraints with compliance 0
// (hard, XPBD only) have no finite energy and are left out. The element
// energies are the shared float math (solver/energy/element_energies.hpp).
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::app {

class EnergyGrowthCheck {
 public:
  // From the run's layout (particles, element sets; copied) and initial
  // velocities (xyz); `factor` 0 turns the check off.
  EnergyGrowthCheck(const solver::SimLayout& layout, std::span<const float> velocities_xyz,
                    std::span<const model::ObjectRange> objects, double factor);

  bool enabled() const { return factor_ > 0.0; }
  double scale() const { return scale_; }

  struct Energy {
    double kinetic = 0.0, elastic = 0.0;
    std::vector<float> velocities;  // xyz, kept to name the element that exploded (positions are the caller's)
    double total() const { return kinetic + elastic; }
  };
  // The energy of a state: positions and velocities as xyz triplets.
  Energy energy(std::span<const float> xyz, std::span<const float> velocities_xyz) const;

  // What blew up between two states, naming the object and element whose
  // energy grew most (the first object's when several alone exceed the
  // limit), or nothing. Updates the growth ratio seen (largest_growth()).
  std::optional<std::string> check(const Energy& before, std::span<const float> xyz_before, const Energy& after,
                                   std::span<const float> xyz_after);
  // The largest (E_after - max(W_g, 0)) / max(E_before, E_scale) seen so far.
  double largest_growth() const { return largest_growth_; }

 private:
  // Per particle (kinetic), then per stretch, bend and tet element (elastic).
  std::vector<float> terms(std::span<const float> xyz, std::span<const float> velocities_xyz) const;
  std::string describe_term(std::size_t term) const;
  int term_vertex(std::size_t term) const;
  int object_of(int vertex) const;

  struct Object {
    std::string name;
    int vertex_offset = 0, vertex_count = 0;
  };
  mutable solver::SimLayout layout_;  // x holds the state being measured
  std::vector<Object> objects_;
  double factor_ = 0.0;
  double scale_ = 0.0;
  double largest_growth_ = -INFINITY;  // none checked yet
};

}  // namespace atssim::app
