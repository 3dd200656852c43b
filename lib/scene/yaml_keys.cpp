#include "scene/yaml_keys.hpp"

#include <map>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::scene {

namespace {

int line_of(const YAML::Node& node) { return node.Mark().is_null() ? 0 : node.Mark().line + 1; }

std::string at(const std::string& file, const YAML::Node& node) {
  const int line = line_of(node);
  return line > 0 ? fmt::format("{}:{}", file, line) : file;
}

void check_node(const YAML::Node& node, const std::string& file, int depth, long long& visited) {
  // Aliases can make a small file a huge tree ("billion laughs").
  if (++visited > 10'000'000) {
    throw input_error(
        fmt::format("{}: the scene expands to more than ten million values (through YAML aliases?); "
                    "write it out plainly",
                    at(file, node)));
  }
  if (depth > 64) {
    throw input_error(
        fmt::format("{}: the scene nests more than 64 levels deep; a scene is a few levels of keys", at(file, node)));
  }
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) check_node(item, file, depth + 1, visited);
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, int> seen;
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) {
      throw input_error(
          fmt::format("{}: a key that is a list or a map (a YAML complex key '? …'); write keys as "
                      "plain names, 'key: value'",
                      at(file, entry.first)));
    }
    const std::string key = entry.first.Scalar();
    if (const auto it = seen.find(key); it != seen.end()) {
      throw input_error(fmt::format("{}: duplicate key '{}' (first given on line {}); keep one of them",
                                    at(file, entry.first), key, it->second));
    }
    seen.emplace(key, line_of(entry.first));
    check_node(entry.second, file, depth + 1, visited);
  }
}

}  // namespace

void check_yaml_keys(const YAML::Node& root, const std::string& file) {
  if (!root.IsMap()) {
    throw input_error(
        fmt::format("{}: the scene is {}, not a map of keys; start it with 'simulation:' and "
                    "'objects:' lines (docs/scene-format.md)",
                    at(file, root), root.IsSequence() ? "a list" : "a single value"));
  }
  long long visited = 0;
  check_node(root, file, 0, visited);
}

}  // namespace atssim::scene
