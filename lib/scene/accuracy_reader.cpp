#include "scene/accuracy_reader.hpp"

#include <fmt/format.h>

namespace atssim::scene {

AccuracyDesc read_accuracy(const YamlReader& solver) {
  AccuracyDesc a;
  if (solver.has("tolerance")) {
    const YamlReader t = solver.child("tolerance");
    a.tolerance = t.number();
    if (!(a.tolerance > 0.0 && a.tolerance < 1.0)) {
      t.fail(fmt::format("solver.tolerance is {}", t.node().as<std::string>()),
             "give the relative energy error wanted per substep, 0 < tolerance < 1 (e.g. 1e-2)");
    }
  }
  if (solver.has("budget_ms")) {
    a.budget_ms = solver.child("budget_ms").number_in(0.0, 1e9, true, "milliseconds per frame, > 0");
  }
  if (solver.has("recheck")) a.recheck = solver.child("recheck").integer_in(0, 100000000);
  if (solver.has("methods")) {
    const YamlReader m = solver.child("methods");
    a.methods_where = m.where();
    for (const YamlReader& name : m.sequence()) {
      const std::string text = name.string();
      if (text.empty()) name.fail("a method name is empty", "list methods as atssim methods names them");
      a.methods.push_back(text);
    }
    if (a.methods.empty()) m.fail("solver.methods is empty", "list at least one method, or leave the key out");
    if (!a.active()) {
      m.fail("solver.methods lists the methods a tolerance or a budget chooses from, and there is neither",
             "give solver.tolerance or solver.budget_ms (--tolerance, --budget) too, or use solver.method");
    }
  }
  return a;
}

void emit_accuracy(YAML::Emitter& out, const AccuracyDesc& a) {
  if (a.tolerance > 0.0) out << YAML::Key << "tolerance" << YAML::Value << a.tolerance;
  if (a.budget_ms > 0.0) out << YAML::Key << "budget_ms" << YAML::Value << a.budget_ms;
  if (a.recheck != AccuracyDesc{}.recheck) out << YAML::Key << "recheck" << YAML::Value << a.recheck;
  if (!a.methods.empty()) {
    out << YAML::Key << "methods" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const std::string& m : a.methods) out << m;
    out << YAML::EndSeq;
  }
}

}  // namespace atssim::scene
