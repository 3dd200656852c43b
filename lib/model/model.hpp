#pragma once
// Particles plus only the element sets the scene asks for (DESIGN.md "Model:
// only what the scene requires"). Plain data in double precision; solvers
// convert it to their device layouts.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/collider.hpp"

namespace atssim::model {

using Vec3 = Eigen::Vector3d;

struct Particles {
  std::vector<Vec3> position;
  std::vector<Vec3> velocity;
  std::vector<double> mass;      // lumped; pinned particles keep their mass here
  std::vector<double> inv_mass;  // 0 = pinned
  std::size_t size() const { return position.size(); }
};

// Distance constraints along mesh edges (stretch).
struct EdgeSet {
  std::vector<std::array<int, 2>> edges;
  std::vector<double> rest_length;
  std::vector<double> compliance;  // m/N
  // Rayleigh stiffness-proportional damping beta in s (c = beta / compliance
  // along the spring, kernels/common/energy_spring_damping.h); an edge
  // without an entry (code that fills the vectors itself) is undamped.
  std::vector<double> damping;
  std::size_t size() const { return edges.size(); }
  void add(int a, int b, double rest, double spring_compliance, double beta) {
    damping.resize(edges.size(), 0.0);
    edges.push_back({a, b});
    rest_length.push_back(rest);
    compliance.push_back(spring_compliance);
    damping.push_back(beta);
  }
};

// How a bending stencil measures bending (scene key `bend_model`).
enum class BendKind {
  isometric,  // Bergou et al. 2006: ½ k · scale · |Σ K_i x_i|², zero only for a flat rest shape
  dihedral,   // Grinspun et al. 2003: k · scale · (θ − θ₀)², zero at the rest angle θ₀
};

// Bending stencils: an interior edge (v0, v1) and the opposite vertices v2,
// v3 of its two triangles (kernels/common/element_types.h, ats_bend_c).
struct BendSet {
  std::vector<std::array<int, 4>> stencils;
  std::vector<std::array<double, 4>> weights;  // isometric: K_i (cotangent weights, sum 0); dihedral: 0
  std::vector<double> scale;                   // isometric: 3 / (A0 + A1); dihedral: 3/2 |e|² / (A0 + A1)
  std::vector<double> compliance;              // 1/(N·m)
  std::vector<double> rest_angle;              // dihedral: θ₀ in radians (common/energy_dihedral.h); isometric: 0
  std::vector<BendKind> kind;
  std::size_t size() const { return stencils.size(); }
};

// Elasticity model of a tetrahedron (scene `model:`); the solvers use it.
enum class TetEnergy { neo_hookean, stvk, springs };

// Linear tetrahedra of deformable solids (Sifakis & Barbic 2012, §4): with
// Dm = [x1−x0, x2−x0, x3−x0] at rest, F = Ds·Dm⁻¹. Every tet has positive
// rest volume (validated when the model is built).
struct TetSet {
  std::vector<std::array<int, 4>> tets;       // particle indices
  std::vector<double> rest_volume;            // m³, det(Dm)/6 > 0
  std::vector<Eigen::Matrix3d> rest_inverse;  // Dm⁻¹
  std::vector<double> mu;                     // Lamé μ (shear modulus), Pa
  std::vector<double> lambda;                 // Lamé λ, Pa
  std::vector<TetEnergy> energy;
  std::size_t size() const { return tets.size(); }
};

// One scene object's slice of the particle arrays, for output.
struct ObjectRange {
  std::string name;
  int vertex_offset = 0;
  int vertex_count = 0;
  std::vector<std::array<int, 3>> triangles;  // object-local vertex indices
  std::vector<Vec3> rest_position;
  std::vector<int> pinned;  // object-local indices
  // Solids: object-local tetrahedra; `triangles` then holds their outward
  // surface (faces of exactly one tet), so output and XDMF show the body.
  std::vector<std::array<int, 4>> tetrahedra;
  // The material's Coulomb mu_s, mu_k (`material.friction`); -1: unset.
  std::array<double, 2> friction{-1.0, -1.0};
};

// Contact between the simulated surfaces (scene `contact:`,
// model/contact_surface.hpp): every object's triangles, global indices.
struct ContactSurface {
  std::vector<std::array<int, 3>> triangles;
  double thickness = 0.0;                                // m
  double stiffness = 0.0;                                // relative to m/h², m the mean free surface particle mass
  double query_radius = 0.0;                             // m, detection radius at the start of a substep
  double static_friction = 0.0, kinetic_friction = 0.0;  // Coulomb mu_s, mu_k between the surfaces
};

struct Model {
  Particles particles;
  EdgeSet stretch;  // empty when the scene models no stretch
  BendSet bend;     // empty when the scene models no bending
  std::vector<ObjectRange> objects;
  Vec3 gravity{0.0, -9.81, 0.0};
  // Last, with an initializer: code that aggregate-initializes the members
  // above (app/simulation.cpp) keeps compiling without a warning.
  TetSet tets{};                                    // empty when the scene has no solid
  std::optional<double> ground{};                   // ground plane height (y), if the scene has one
  double air_drag = 0.0;                            // 1/s: force −m·c·v on every particle
  std::vector<Collider> colliders{};                // analytic obstacles (model/collider.hpp)
  std::optional<ContactSurface> contact_surface{};  // self/cloth-cloth/cloth-solid contact, when the scene asks
};

}  // namespace atssim::model
