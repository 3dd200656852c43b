#include "scene/scene_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include "scene/accuracy_reader.hpp"
#include "scene/collider_reader.hpp"
#include "scene/contact_reader.hpp"

namespace atssim::scene {

namespace {

template <typename Array>
void flow_seq(YAML::Emitter& out, const Array& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const auto& v : values) out << v;
  out << YAML::EndSeq;
}

const char* bend_model_name(BendModel model) {
  switch (model) {
    case BendModel::isometric:
      return "isometric";
    case BendModel::dihedral:
      return "dihedral";
    case BendModel::automatic:
      break;
  }
  return "auto";
}

void emit_object(YAML::Emitter& out, const ObjectDesc& obj) {
  out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << obj.name;
  const bool solid = obj.type == ObjectType::solid;
  out << YAML::Key << "type" << YAML::Value << (solid ? "solid" : "cloth");
  if (obj.box) {
    out << YAML::Key << "box" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "size" << YAML::Value;
    flow_seq(out, obj.box->size);
    out << YAML::Key << "resolution" << YAML::Value;
    flow_seq(out, obj.box->resolution);
    out << YAML::EndMap;
  } else if (obj.grid) {
    out << YAML::Key << "grid" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "size" << YAML::Value;
    flow_seq(out, obj.grid->size);
    out << YAML::Key << "resolution" << YAML::Value;
    flow_seq(out, obj.grid->resolution);
    out << YAML::EndMap;
  } else {
    out << YAML::Key << "mesh" << YAML::Value << obj.mesh_path;
  }
  out << YAML::Key << "transform" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "translate" << YAML::Value;
  flow_seq(out, obj.transform.translate);
  out << YAML::Key << "rotate" << YAML::Value;
  flow_seq(out, obj.transform.rotate_deg);
  out << YAML::Key << "scale" << YAML::Value;
  flow_seq(out, obj.transform.scale);
  out << YAML::EndMap;
  const MaterialDesc& m = obj.material;
  out << YAML::Key << "material" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "density" << YAML::Value << m.density;
  if (solid) {
    out << YAML::Key << "youngs_modulus" << YAML::Value << m.youngs_modulus;
    out << YAML::Key << "poisson_ratio" << YAML::Value << m.poisson_ratio;
    out << YAML::Key << "model" << YAML::Value << std::string(to_string(m.solid_model));
  }
  if (m.has_stretch) out << YAML::Key << "stretch_compliance" << YAML::Value << m.stretch_compliance;
  if (m.has_bending) out << YAML::Key << "bend_compliance" << YAML::Value << m.bend_compliance;
  if (m.has_bending) out << YAML::Key << "bend_model" << YAML::Value << bend_model_name(m.bend_model);
  if (m.cloth_springs) {
    out << YAML::Key << "model" << YAML::Value << "springs";
    out << YAML::Key << "shear_stiffness" << YAML::Value << m.shear_stiffness;
    out << YAML::Key << "bend_spring_stiffness" << YAML::Value << m.bend_spring_stiffness;
  }
  if (m.damping > 0.0) out << YAML::Key << "damping" << YAML::Value << m.damping;
  if (m.has_friction) {
    out << YAML::Key << "friction" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "static"
        << YAML::Value << m.static_friction << YAML::Key << "kinetic" << YAML::Value << m.kinetic_friction
        << YAML::EndMap;
  }
  out << YAML::EndMap;
  if (!obj.pins.vertices.empty() || !obj.pins.boxes.empty()) {
    out << YAML::Key << "pins" << YAML::Value << YAML::BeginMap;
    if (!obj.pins.vertices.empty()) {
      out << YAML::Key << "vertices" << YAML::Value;
      flow_seq(out, obj.pins.vertices);
    }
    if (!obj.pins.boxes.empty()) {
      out << YAML::Key << "boxes" << YAML::Value << YAML::BeginSeq;
      for (const BoxDesc& b : obj.pins.boxes) {
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "min" << YAML::Value;
        flow_seq(out, b.min);
        out << YAML::Key << "max" << YAML::Value;
        flow_seq(out, b.max);
        out << YAML::EndMap;
      }
      out << YAML::EndSeq;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace

std::string_view to_string(SolidModel model) {
  switch (model) {
    case SolidModel::stvk:
      return "stvk";
    case SolidModel::springs:
      return "springs";
    case SolidModel::neo_hookean:
      break;
  }
  return "neo_hookean";
}

std::string to_resolved_yaml(const SceneDesc& scene) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  const SimulationDesc& s = scene.simulation;
  out << YAML::Key << "simulation" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "dt" << YAML::Value << s.frame_dt;
  out << YAML::Key << "substeps" << YAML::Value << s.substeps;
  out << YAML::Key << "iterations" << YAML::Value << s.iterations;
  out << YAML::Key << "frames" << YAML::Value << s.frames;
  out << YAML::Key << "gravity" << YAML::Value;
  flow_seq(out, s.gravity);
  if (s.ground) out << YAML::Key << "ground" << YAML::Value << *s.ground;
  if (s.air_drag > 0.0) out << YAML::Key << "air_drag" << YAML::Value << s.air_drag;
  if (s.energy_growth_limit != SimulationDesc{}.energy_growth_limit) {
    out << YAML::Key << "energy_growth_limit" << YAML::Value << s.energy_growth_limit;
  }
  out << YAML::EndMap;
  out << YAML::Key << "objects" << YAML::Value << YAML::BeginSeq;
  for (const ObjectDesc& obj : scene.objects) emit_object(out, obj);
  out << YAML::EndSeq;
  if (!scene.colliders.empty()) {
    out << YAML::Key << "colliders" << YAML::Value << YAML::BeginSeq;
    for (const ColliderDesc& c : scene.colliders) emit_collider(out, c);
    out << YAML::EndSeq;
  }
  emit_self_contact(out, scene.contact);
  const SolverDesc& solver = scene.solver;
  out << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "method" << YAML::Value << solver.method;
  out << YAML::Key << "schedule" << YAML::Value << solver.schedule;
  out << YAML::Key << "async_depth" << YAML::Value << solver.async_depth;
  out << YAML::Key << "merge" << YAML::Value << solver.merge;
  out << YAML::Key << "async_fetch" << YAML::Value << (solver.async_latest ? "latest" : "dependencies");
  out << YAML::Key << "replay" << YAML::Value << (solver.replay ? "true" : "false");
  out << YAML::Key << "task_merging" << YAML::Value << (solver.task_merging ? "auto" : "off");
  out << YAML::Key << "executor" << YAML::Value << solver.executor;
  out << YAML::Key << "wait_timeout" << YAML::Value << solver.wait_timeout_s;
  emit_accuracy(out, solver.accuracy);
  for (const MethodOptionDesc& o : solver.method_options) {
    // The value as written; text that is no YAML of its own (a quoted
    // string holding ": ") is kept as a string (found by fuzzing).
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception&) {
      value = YAML::Node(o.value);
    }
    out << YAML::Key << o.key << YAML::Value << value;
  }
  out << YAML::EndMap;
  out << YAML::Key << "output" << YAML::Value << YAML::BeginMap << YAML::Key << "path" << YAML::Value
      << scene.output.path << YAML::Key << "stride" << YAML::Value << scene.output.stride << YAML::EndMap;
  out << YAML::Key << "devices" << YAML::Value << scene.devices;
  out << YAML::Key << "memory" << YAML::Value << scene.memory;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace atssim::scene
