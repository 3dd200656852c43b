#include "solver/method.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::solver {

double MethodSettings::option(std::string_view key) const {
  const auto it = options.find(key);
  if (it == options.end()) throw internal_error(fmt::format("method option '{}' was not resolved", key));
  return it->second;
}

double MethodSettings::option_or(std::string_view key, double fallback) const {
  return given.contains(key) ? option(key) : fallback;
}

std::string MethodOption::default_text() const {
  const auto i = static_cast<std::size_t>(default_value);
  if (!choices.empty() && i < choices.size()) return std::string(choices[i]);
  return fmt::format("{}", default_value);
}

bool MethodDescription::simulates(scene::SolidModel model) const {
  return std::find(solid_models.begin(), solid_models.end(), model) != solid_models.end();
}

}  // namespace atssim::solver
