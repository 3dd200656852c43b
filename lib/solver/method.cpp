#include "solver/method.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::solver {

double MethodSettings::option(std::string_view key) const {
  const auto it = options.find(key);
  if (it == options.end()) throw Error(fmt::format("internal error: method option '{}' was not resolved", key));
  return it->second;
}

bool MethodDescription::simulates(scene::SolidModel model) const {
  return std::find(solid_models.begin(), solid_models.end(), model) != solid_models.end();
}

}  // namespace atssim::solver
