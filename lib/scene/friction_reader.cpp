#include "scene/friction_reader.hpp"

#include <array>
#include <string_view>

#include <fmt/format.h>

namespace atssim::scene {

namespace {

constexpr std::array<std::string_view, 2> kFrictionKeys{"static", "kinetic"};

double coefficient(const YamlReader& r) {
  const double v = r.number();
  if (v < 0.0 || v > 100.0) {
    r.fail(fmt::format("'{}' is {}, but a friction coefficient lies from 0 to 100", r.path(), r.node().Scalar()),
           "use 0 for none, e.g. 0.3 for cloth on wood");
  }
  return v;
}

}  // namespace

FrictionDesc read_friction(const YamlReader& r) {
  FrictionDesc f;
  if (r.node().IsScalar()) {
    f.static_coefficient = f.kinetic_coefficient = coefficient(r);
    return f;
  }
  r.expect_map(kFrictionKeys);
  if (r.has("static")) f.static_coefficient = coefficient(r.child("static"));
  f.kinetic_coefficient = r.has("kinetic") ? coefficient(r.child("kinetic")) : f.static_coefficient;
  if (!r.has("static")) f.static_coefficient = f.kinetic_coefficient;
  return f;
}

}  // namespace atssim::scene
