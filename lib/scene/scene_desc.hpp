#pragma once
// What the user asked for, validated (DESIGN.md pipeline stage 1). Plain
// data; every value is in SI units and already range-checked.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/accuracy_desc.hpp"
#include "scene/collider_desc.hpp"
#include "scene/contact_desc.hpp"

namespace atssim::scene {

using Vec3 = std::array<double, 3>;

struct SimulationDesc {
  double frame_dt = 1.0 / 60.0;  // seconds per frame (from fps or dt)
  int substeps = 16;
  int iterations = 8;
  int frames = 60;
  Vec3 gravity{0.0, -9.81, 0.0};
  // Height of a ground plane y = ground that no particle goes below (the
  // only collider of this version: a projection at the end of every
  // iteration, no friction); absent = no ground.
  std::optional<double> ground;
  // Air drag: every free particle feels −m·c·v (c in 1/s; a body moving
  // alone slows as e^(−c t)); implicit in every method (solver/layout).
  double air_drag = 0.0;
  // A frame whose kinetic + elastic energy grows by more than this factor
  // (beyond gravity's work) blew up (app/energy_growth.hpp); 0 = no check.
  double energy_growth_limit = 1000.0;
};

struct GridDesc {
  std::array<double, 2> size{1.0, 1.0};   // metres along local x and z
  std::array<int, 2> resolution{32, 32};  // vertices along x and z (≥ 2 each)
};

struct TransformDesc {
  Vec3 translate{0.0, 0.0, 0.0};
  Vec3 rotate_deg{0.0, 0.0, 0.0};  // applied about x, then y, then z
  Vec3 scale{1.0, 1.0, 1.0};
};

// A tetrahedral body's elasticity model (issue #6).
enum class SolidModel { neo_hookean, stvk, springs };
// Its name in a scene (material.model): "neo_hookean", "stvk", "springs".
std::string_view to_string(SolidModel model);

// Cloth bending model (`bend_model`): automatic = dihedral when the rest
// shape is curved (some rest dihedral angle above 1e-4 rad), else isometric.
enum class BendModel { automatic, isometric, dihedral };

struct MaterialDesc {
  double density = 0.2;             // kg/m² for cloth, kg/m³ for solids (default 1000 there)
  double stretch_compliance = 0.0;  // cloth: m/N (inverse stiffness); used when has_stretch
  bool has_stretch = false;
  double bend_compliance = 0.0;  // cloth: 1/(N·m); used when has_bending
  bool has_bending = false;
  BendModel bend_model = BendModel::automatic;  // cloth
  double damping = 0.0;                         // s: Rayleigh β of the springs (c = β k along each), ≥ 0
  bool cloth_springs = false;                   // cloth `model: springs`: structural, shear, bending springs
  double shear_stiffness = 0.0;                 // cloth springs: N/m per shear spring (0 = none)
  double bend_spring_stiffness = 0.0;           // cloth springs: N/m per bending spring (0 = none)
  double youngs_modulus = 1.0e5;                // solids: Pa (> 0)
  double poisson_ratio = 0.3;                   // solids: 0 ≤ ν < 0.5
  SolidModel solid_model = SolidModel::neo_hookean;
  // Coulomb coefficients of the object's surface (`friction:`); unset: a
  // collider's own decide, and between surfaces contact.friction.
  bool has_friction = false;
  double static_friction = 0.0, kinetic_friction = 0.0;
  std::string model_where;            // "file:line" (or the --set) that chose solid_model; empty = default
  std::string zero_compliance_where;  // "file:line" of a compliance of 0 (perfectly stiff); empty = none
};

struct BoxDesc {
  Vec3 min{0.0, 0.0, 0.0};
  Vec3 max{0.0, 0.0, 0.0};
};

struct PinDesc {
  std::vector<int> vertices;   // indices into the object's vertices
  std::vector<BoxDesc> boxes;  // world-space boxes: every vertex inside is pinned
};

// A triangle mesh as read from a file: vertices welded by position.
struct TriangleMesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
};

// A tetrahedral mesh as read from a file (TetGen .node/.ele, Gmsh .msh) or
// made procedurally. `element_line`/`element_label` say where each element
// came from, so validation can name the file line and the file's own number.
struct TetMesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 4>> tetrahedra;
  std::string file;                      // "" for procedural meshes
  std::vector<int> element_line;         // 1-based line in `file` (empty when procedural)
  std::vector<long long> element_label;  // the element's number in `file` (empty when procedural)
};

// A procedural tetrahedral box centred on the origin; every cell is split
// into 6 tetrahedra.
struct TetBoxDesc {
  Vec3 size{1.0, 1.0, 1.0};                // metres along local x, y, z
  std::array<int, 3> resolution{4, 4, 4};  // cells along x, y, z (≥ 1 each)
};

enum class ObjectType { cloth, solid };

struct ObjectDesc {
  std::string name;
  ObjectType type = ObjectType::cloth;
  std::optional<GridDesc> grid;   // cloth: exactly one of grid / mesh_path
  std::optional<TetBoxDesc> box;  // solid: exactly one of box / mesh_path
  std::string mesh_path;          // absolute, resolved against the scene's folder
  TriangleMesh mesh;              // cloth: loaded when mesh_path is set
  TetMesh tet_mesh;               // solid: loaded when mesh_path is set
  TransformDesc transform;
  MaterialDesc material;
  PinDesc pins;
  int source_line = 0;  // 1-based line of the object in the scene file
};

// A key under `solver:` that is no schedule key: an option of a method, kept
// as written with the line it came from; the method registry
// (lib/solver/method_registry.hpp) checks it against the methods' options.
struct MethodOptionDesc {
  std::string key;
  std::string value;
  std::string where;  // "file:line" or the --set
};

struct SolverDesc {
  std::string method = "xpbd";
  std::string method_where;                      // "file:line" (or the --set) that chose the method; empty = default
  std::string schedule_where;                    // "file:line" (or the --set) that chose the schedule; empty = default
  std::string schedule = "single";               // single | split | heft | async: how the substep uses the devices
  int async_depth = 2;                           // async: iterations in flight at once (1 = serial Gauss-Seidel)
  std::string merge = "average_displacements";   // async: how a device merges another's result
  bool async_latest = true;                      // async: also merge the latest finished result, not only dependencies
  bool replay = false;                           // async: run the schedule on one device, in schedule order
  bool task_merging = true;                      // heft: merge colour blocks where predicted to pay (auto | off)
  std::string executor = "auto";                 // auto | fused | events: how the devices run the schedule
  double wait_timeout_s = 10.0;                  // fused: a run in which no task finishes this long fails
  std::vector<MethodOptionDesc> method_options;  // every other key, in file order (then --set ones)
  AccuracyDesc accuracy;                         // tolerance / budget_ms: atssim chooses method and iterations
};

struct OutputDesc {
  std::string path = "out.h5";  // resolved against the working directory
  int stride = 1;               // write every stride-th frame
};

struct SceneDesc {
  std::string source_path;    // the scene file ("" for text scenes)
  std::string yaml_text;      // as given
  std::string resolved_yaml;  // after defaults and --set overrides
  SimulationDesc simulation;
  std::vector<ObjectDesc> objects;
  std::vector<ColliderDesc> colliders;  // analytic obstacles (empty = none: no contact tasks)
  SelfContactDesc contact;              // contact between the simulated surfaces (off = no such tasks)
  SolverDesc solver;
  OutputDesc output;
  std::string devices = "default";  // device spec, see `atssim devices`
  std::string devices_where;        // "file:line" (or the --set) that gave it; empty = default
  std::string memory = "shared";    // shared (a platform's devices share SVM) | separate (copies through the host)
};

}  // namespace atssim::scene
