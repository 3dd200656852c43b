#include "scene/object_reader.hpp"

#include <array>

#include <cmath>
#include <span>

#include <fmt/format.h>

#include "scene/friction_reader.hpp"
#include "scene/mesh_loader.hpp"
#include "scene/tet_mesh_loader.hpp"
#include "util/did_you_mean.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

namespace fs = std::filesystem;
using Keys = std::span<const std::string_view>;

constexpr std::array<std::string_view, 8> kObjectKeys{"name", "type",      "grid",     "box",
                                                      "mesh", "transform", "material", "pins"};
constexpr std::array<std::string_view, 2> kGridKeys{"size", "resolution"};
constexpr std::array<std::string_view, 3> kTransformKeys{"translate", "rotate", "scale"};
constexpr std::array<std::string_view, 13> kMaterialKeys{"density",        "stretch_stiffness", "stretch_compliance",
                                                         "bend_stiffness", "bend_compliance",   "bend_model",
                                                         "youngs_modulus", "poisson_ratio",     "model",
                                                         "damping",        "shear_stiffness",   "bend_spring_stiffness",
                                                         "friction"};
// Keys that only one object type takes; on the other type they are an error
// that says so, rather than being silently ignored.
constexpr std::array<std::string_view, 7> kClothOnlyMaterialKeys{
    "stretch_stiffness", "stretch_compliance", "bend_stiffness",       "bend_compliance",
    "bend_model",        "shear_stiffness",    "bend_spring_stiffness"};
constexpr std::array<std::string_view, 2> kClothModels{"triangles", "springs"};
constexpr std::array<std::string_view, 3> kBendModels{"auto", "isometric", "dihedral"};
constexpr std::array<std::string_view, 2> kSolidOnlyMaterialKeys{"youngs_modulus", "poisson_ratio"};
constexpr std::array<std::string_view, 3> kSolidModels{"neo_hookean", "stvk", "springs"};
constexpr double kSolidDefaultDensity = 1000.0;  // kg/m³, water
constexpr long long kMaxBoxCells = 4'000'000;    // 24 M tetrahedra
constexpr std::array<std::string_view, 2> kPinKeys{"vertices", "boxes"};
constexpr std::array<std::string_view, 2> kBoxKeys{"min", "max"};

constexpr double kHuge = 1e30;
constexpr double kFarthest = 1e8;  // m: float32 positions lose all precision beyond

void check_lengths(const YamlReader& r, std::span<const double> values, std::string_view what) {
  for (double v : values) {
    if (std::abs(v) > kFarthest) {
      r.fail(fmt::format("{} {:g} m is absurd (further than {:g} m, where float32 positions lose all precision)", what,
                         v, kFarthest),
             "give metres within ±1e8");
    }
  }
}

GridDesc read_grid(const YamlReader& r) {
  r.expect_map(kGridKeys);
  GridDesc grid;
  if (r.has("size")) {
    grid.size = r.child("size").vec2();
    for (double s : grid.size) {
      if (s <= 0.0) r.child("size").fail("grid size must be positive", "give the side lengths in metres, e.g. [1, 1]");
    }
    check_lengths(r.child("size"), grid.size, "grid size");
  }
  if (r.has("resolution")) {
    const auto res = r.child("resolution").sequence();
    if (res.size() != 2) r.child("resolution").fail("resolution needs two entries", "write [nx, nz]");
    grid.resolution = {res[0].integer_in(2, 8192), res[1].integer_in(2, 8192)};
  }
  return grid;
}

TransformDesc read_transform(const YamlReader& r) {
  TransformDesc t;
  r.expect_map(kTransformKeys);
  if (r.has("translate")) {
    t.translate = r.child("translate").vec3();
    check_lengths(r.child("translate"), t.translate, "translation");
  }
  if (r.has("rotate")) t.rotate_deg = r.child("rotate").vec3();
  if (r.has("scale")) {
    const YamlReader s = r.child("scale");
    if (s.node().IsScalar()) {
      const double k = s.number_in(0.0, 1e6, true, "a scale factor, 0 < scale ≤ 1e6");
      t.scale = {k, k, k};
    } else {
      t.scale = s.vec3();
      for (double k : t.scale) {
        if (k <= 0.0 || k > 1e6) s.fail("scale factors must be positive and at most 1e6", "use e.g. [1, 1, 1]");
      }
    }
  }
  return t;
}

// stiffness k > 0 -> compliance 1/k; stiffness 0 -> term not modelled;
// compliance c ≥ 0 -> modelled (0 = inextensible / perfectly stiff).
void read_stiffness_pair(const YamlReader& r, const char* stiffness_key, const char* compliance_key, double& compliance,
                         bool& modelled, std::string& zero_compliance_where) {
  if (r.has(stiffness_key) && r.has(compliance_key)) {
    r.child(compliance_key)
        .fail(fmt::format("both '{}' and '{}' are given", stiffness_key, compliance_key),
              "keep one of them (compliance = 1/stiffness)");
  }
  if (r.has(stiffness_key)) {
    const double k = r.child(stiffness_key).number_in(0.0, kHuge, false, "a stiffness ≥ 0 (0 turns the term off)");
    modelled = k > 0.0;
    compliance = modelled ? 1.0 / k : 0.0;
  } else if (r.has(compliance_key)) {
    compliance = r.child(compliance_key).number_in(0.0, kHuge, false, "a compliance ≥ 0 (0 = perfectly stiff)");
    modelled = true;
    if (compliance == 0.0 && zero_compliance_where.empty()) zero_compliance_where = r.child(compliance_key).where();
  }
}

BendModel read_bend_model(const YamlReader& k) {
  const std::string name = k.string();
  if (name == "auto") return BendModel::automatic;
  if (name == "isometric") return BendModel::isometric;
  if (name == "dihedral") return BendModel::dihedral;
  const std::string guess = closest_match(name, kBendModels);
  k.fail(fmt::format("unknown bend_model '{}'", name),
         guess.empty() ? "use auto, isometric or dihedral" : fmt::format("did you mean '{}'?", guess));
  return BendModel::automatic;
}

void read_solid_material(const YamlReader& r, MaterialDesc& m) {
  if (r.has("youngs_modulus")) {
    m.youngs_modulus = r.child("youngs_modulus").number_in(0.0, kHuge, true, "a Young's modulus in Pa > 0, e.g. 1e5");
  }
  if (r.has("poisson_ratio")) {
    const YamlReader p = r.child("poisson_ratio");
    m.poisson_ratio = p.number_in(0.0, 0.5, false, "a Poisson ratio 0 ≤ ν < 0.5, e.g. 0.3");
    if (m.poisson_ratio >= 0.5) {
      p.fail("'poisson_ratio' is 0.5, out of range",
             "use 0 ≤ ν < 0.5 (0.5 is incompressible and makes λ infinite), e.g. 0.45");
    }
  }
  if (r.has("model")) {
    const YamlReader k = r.child("model");
    const std::string name = k.string();
    m.model_where = k.where();
    if (name == "neo_hookean") {
      m.solid_model = SolidModel::neo_hookean;
    } else if (name == "stvk") {
      m.solid_model = SolidModel::stvk;
    } else if (name == "springs") {
      m.solid_model = SolidModel::springs;
    } else {
      const std::string guess = closest_match(name, kSolidModels);
      k.fail(fmt::format("unknown solid model '{}'", name),
             guess.empty() ? "use neo_hookean, stvk or springs" : fmt::format("did you mean '{}'?", guess));
    }
  }
}

// Cloth `model: triangles` (the default: edge springs and bending stencils)
// or `springs` (model/cloth_springs.hpp), with the springs' stiffnesses.
void read_cloth_springs(const YamlReader& r, MaterialDesc& m) {
  if (r.has("model")) {
    const YamlReader k = r.child("model");
    const std::string name = k.string();
    if (name == "springs") {
      m.cloth_springs = true;
    } else if (name != "triangles") {
      const std::string guess = closest_match(name, kClothModels);
      k.fail(fmt::format("unknown cloth model '{}'", name),
             guess.empty() ? "use triangles or springs" : fmt::format("did you mean '{}'?", guess));
    }
  }
  for (std::string_view key : {std::string_view("shear_stiffness"), std::string_view("bend_spring_stiffness")}) {
    if (!r.has(key)) continue;
    const YamlReader k = r.child(key);
    if (!m.cloth_springs) k.fail(fmt::format("'{}' is a key of mass-spring cloth", key), "add 'model: springs'");
    const double value = k.number_in(0.0, kHuge, false, "a stiffness in N/m ≥ 0 (0 = no such springs)");
    (key == "shear_stiffness" ? m.shear_stiffness : m.bend_spring_stiffness) = value;
  }
}

MaterialDesc read_material(const YamlReader& r, ObjectType type, const std::string& object) {
  MaterialDesc m;
  const bool solid = type == ObjectType::solid;
  if (solid) m.density = kSolidDefaultDensity;
  if (r.is_null()) return m;
  r.expect_map(kMaterialKeys);
  for (std::string_view key : solid ? Keys(kClothOnlyMaterialKeys) : Keys(kSolidOnlyMaterialKeys)) {
    if (!r.has(key)) continue;
    r.child(key).fail(fmt::format("'{}' is a {} material key, but object '{}' is a {}", key, solid ? "cloth" : "solid",
                                  object, solid ? "solid" : "cloth"),
                      solid ? "remove it (solids take density, youngs_modulus, poisson_ratio and model)"
                            : "remove it, or add 'type: solid' to the object");
  }
  if (r.has("density")) {
    m.density = r.child("density").number_in(
        0.0, kHuge, true, solid ? "a density > 0 (kg/m³ for solids)" : "a density > 0 (kg/m² for cloth)");
  }
  if (solid) {
    read_solid_material(r, m);
  } else {
    read_stiffness_pair(r, "stretch_stiffness", "stretch_compliance", m.stretch_compliance, m.has_stretch,
                        m.zero_compliance_where);
    read_stiffness_pair(r, "bend_stiffness", "bend_compliance", m.bend_compliance, m.has_bending,
                        m.zero_compliance_where);
    if (r.has("bend_model")) m.bend_model = read_bend_model(r.child("bend_model"));
    read_cloth_springs(r, m);
  }
  if (r.has("friction")) {
    const FrictionDesc f = read_friction(r.child("friction"));
    m.has_friction = true;
    m.static_friction = f.static_coefficient;
    m.kinetic_friction = f.kinetic_coefficient;
  }
  if (r.has("damping")) {
    const YamlReader d = r.child("damping");
    m.damping = d.number_in(0.0, 1e3, false, "a damping time β in s ≥ 0 (each spring gets c = β k), e.g. 0.001");
    if (solid && m.damping > 0.0 && m.solid_model != SolidModel::springs) {
      d.fail("'damping' damps springs, and this solid's model is not springs",
             "set 'model: springs', or remove it and damp with simulation.air_drag");
    }
  }
  return m;
}

PinDesc read_pins(const YamlReader& r) {
  PinDesc pins;
  r.expect_map(kPinKeys);
  if (r.has("vertices")) {
    pins.vertices = r.child("vertices").int_list();
    for (int v : pins.vertices) {
      if (v < 0) r.child("vertices").fail(fmt::format("vertex index {} is negative", v), "use indices ≥ 0");
    }
  }
  if (r.has("boxes")) {
    for (const YamlReader& b : r.child("boxes").sequence()) {
      b.expect_map(kBoxKeys);
      if (!b.has("min") || !b.has("max"))
        b.fail("a pin box needs 'min' and 'max'", "write {min: [x,y,z], max: [x,y,z]}");
      BoxDesc box{b.child("min").vec3(), b.child("max").vec3()};
      for (int k = 0; k < 3; ++k) {
        if (box.min[k] > box.max[k]) b.fail("pin box has min > max", "swap the corners");
      }
      pins.boxes.push_back(box);
    }
  }
  return pins;
}

TetBoxDesc read_tet_box(const YamlReader& r) {
  r.expect_map(kGridKeys);
  TetBoxDesc box;
  if (r.has("size")) {
    box.size = r.child("size").vec3();
    for (double s : box.size) {
      if (s <= 0.0)
        r.child("size").fail("box size must be positive", "give the side lengths in metres, e.g. [1, 1, 1]");
    }
    check_lengths(r.child("size"), box.size, "box size");
  }
  if (r.has("resolution")) {
    const auto res = r.child("resolution").sequence();
    if (res.size() != 3) r.child("resolution").fail("resolution needs three entries", "write [nx, ny, nz] (cells)");
    box.resolution = {res[0].integer_in(1, 4096), res[1].integer_in(1, 4096), res[2].integer_in(1, 4096)};
    const long long cells = 1LL * box.resolution[0] * box.resolution[1] * box.resolution[2];
    if (cells > kMaxBoxCells) {
      r.child("resolution")
          .fail(fmt::format("the box has {} cells ({} tetrahedra)", cells, 6 * cells),
                fmt::format("use at most {} cells in all", kMaxBoxCells));
    }
  }
  return box;
}

ObjectType read_type(const YamlReader& r) {
  if (!r.has("type")) return ObjectType::cloth;
  const YamlReader t = r.child("type");
  const std::string type = t.string();
  if (type == "cloth") return ObjectType::cloth;
  if (type == "solid") return ObjectType::solid;
  t.fail(fmt::format("unknown object type '{}'", type), "use cloth (a triangle surface) or solid (a tetrahedral body)");
}

// Shape keys: a cloth takes grid or a surface mesh, a solid box or a tet mesh.
void read_shape(const YamlReader& r, ObjectDesc& obj, const fs::path& base_dir) {
  const bool solid = obj.type == ObjectType::solid;
  if (solid && r.has("grid")) {
    r.child("grid").fail(fmt::format("'grid' makes a cloth, but object '{}' is a solid", obj.name),
                         "use box: {size: [x, y, z], resolution: [nx, ny, nz]}, or remove 'type: solid'");
  }
  if (!solid && r.has("box")) {
    r.child("box").fail(fmt::format("'box' makes a solid, but object '{}' is a cloth", obj.name),
                        "add 'type: solid' to the object, or use grid: for a cloth");
  }
  const char* shape = solid ? "box" : "grid";
  const bool has_shape = r.has(shape);
  const bool has_mesh = r.has("mesh");
  if (has_shape == has_mesh) {
    r.fail(fmt::format("object '{}' needs exactly one of '{}' or 'mesh'", obj.name, shape),
           solid ? "give box: {size: [1, 1, 1], resolution: [4, 4, 4]} or mesh: body.msh (or body.node)"
                 : "give grid: {size: [1, 1], resolution: [32, 32]} or mesh: cloth.obj");
  }
  if (has_shape && solid) obj.box = read_tet_box(r.child("box"));
  if (has_shape && !solid) obj.grid = read_grid(r.child("grid"));
  if (!has_mesh) return;
  const YamlReader m = r.child("mesh");
  fs::path p(m.string());
  if (p.is_relative()) p = base_dir / p;
  obj.mesh_path = p.lexically_normal().string();
  if (solid && !is_tet_mesh_path(obj.mesh_path)) {
    m.fail(fmt::format("object '{}' is a solid, but '{}' is not a tetrahedral mesh", obj.name, m.string()),
           "give a TetGen .node/.ele pair or a Gmsh .msh file");
  }
  if (!solid && is_tet_mesh_path(obj.mesh_path)) {
    m.fail(fmt::format("'{}' is a tetrahedral mesh, but object '{}' is a cloth", m.string(), obj.name),
           "add 'type: solid' to simulate it as a deformable body");
  }
  if (solid) {
    obj.tet_mesh = load_tet_mesh(obj.mesh_path, m.where());
  } else {
    obj.mesh = load_triangle_mesh(obj.mesh_path, m.where());
  }
}

}  // namespace

ObjectDesc read_object(const YamlReader& r, int index, const fs::path& base_dir) {
  r.expect_map(kObjectKeys);
  ObjectDesc obj;
  obj.source_line = r.line();
  obj.name = r.has("name") ? r.child("name").string() : fmt::format("object{}", index);
  if (r.has("name")) {
    const YamlReader n = r.child("name");
    if (obj.name.empty() || obj.name.find_first_not_of(" \t") == std::string::npos) {
      n.fail("the object's name is empty", "give it a name such as 'cloth' (or leave 'name' out)");
    }
    if (obj.name.find_first_of("/\\") != std::string::npos || obj.name == "." || obj.name == "..") {
      n.fail(fmt::format("object name '{}' contains '/' or is '.'/'..' (it names a group in the output)", obj.name),
             "use letters, digits, '_' or '-'");
    }
    if (obj.name.size() > 255) n.fail("the object's name is longer than 255 characters", "use a shorter name");
  }
  obj.type = read_type(r);
  read_shape(r, obj, base_dir);
  if (r.has("transform")) obj.transform = read_transform(r.child("transform"));
  obj.material = read_material(r.child("material"), obj.type, obj.name);
  if (r.has("pins")) obj.pins = read_pins(r.child("pins"));
  return obj;
}

}  // namespace atssim::scene
