#include "scene/yaml_keys.hpp"

#include <map>

#include <fmt/format.h>

#include "scene/yaml_reader.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

int line_of(const YAML::Node& node) { return node.Mark().is_null() ? 0 : node.Mark().line + 1; }

// Where a node is: "file:line", or only `where` for a value given on the
// command line (its lines are those of the --set text).
struct Place {
  std::string where;
  bool lines = true;
};

std::string at(const Place& place, const YAML::Node& node) {
  const int line = place.lines ? line_of(node) : 0;
  return line > 0 ? fmt::format("{}:{}", place.where, line) : place.where;
}

// The tags YAML's core schema defines for what a scene holds; a value
// tagged otherwise (!!binary, !!timestamp, an application's !tag) would be
// read as plain text with the tag silently dropped.
void check_tag(const YAML::Node& node, const Place& file) {
  const std::string& tag = node.Tag();
  if (tag.empty() || tag == "?" || tag == "!") return;
  static const char* const kCore[] = {"str", "int", "float", "bool", "null", "map", "seq"};
  for (const char* name : kCore) {
    if (tag == std::string("tag:yaml.org,2002:") + name) return;
  }
  const std::string shown = tag.rfind("tag:yaml.org,2002:", 0) == 0 ? "!!" + tag.substr(18) : tag;
  throw input_error(
      fmt::format("{}: the YAML tag '{}' means nothing in a scene; remove it", at(file, node), one_line(shown)));
}

// Aliases can make a small file a huge tree ("billion laughs"). The largest
// bundled scene holds a few hundred values; a million is walked in well under
// a second, also under the fuzzer's sanitizers.
constexpr long long kMaxValues = 1'000'000;

void check_node(const YAML::Node& node, const Place& file, int depth, long long& visited) {
  if (++visited > kMaxValues) {
    throw input_error(
        fmt::format("{}: the scene expands to more than one million values (through YAML aliases?); "
                    "write it out plainly",
                    at(file, node)));
  }
  if (depth > 64) {
    throw input_error(
        fmt::format("{}: the scene nests more than 64 levels deep; a scene is a few levels of keys", at(file, node)));
  }
  check_tag(node, file);
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
    if (key == "<<" && entry.first.Tag() == "?") {
      throw input_error(
          fmt::format("{}: a YAML merge key ('<<: *anchor'), which atssim does not read; write the keys out (an "
                      "alias of a whole value, 'material: *soft', works)",
                      at(file, entry.first)));
    }
    if (const auto it = seen.find(key); it != seen.end()) {
      throw input_error(fmt::format("{}: duplicate key '{}' (first given on line {}); keep one of them",
                                    at(file, entry.first), one_line(key), it->second));
    }
    seen.emplace(key, line_of(entry.first));
    check_node(entry.second, file, depth + 1, visited);
  }
}

}  // namespace

void check_yaml_keys(const YAML::Node& root, const std::string& file) {
  const Place place{file, true};
  if (!root.IsMap()) {
    throw input_error(
        fmt::format("{}: the scene is {}, not a map of keys; start it with 'simulation:' and "
                    "'objects:' lines (docs/scene-format.md)",
                    at(place, root), root.IsSequence() ? "a list" : "a single value"));
  }
  long long visited = 0;
  check_node(root, place, 0, visited);
}

void check_yaml_value(const YAML::Node& value, const std::string& where) {
  long long visited = 0;
  check_node(value, Place{where, false}, 0, visited);
}

}  // namespace atssim::scene
