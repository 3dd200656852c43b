#pragma once
// Typed, checked access to YAML nodes. Every error names the file, the line
// and the fix, and suggests the closest key for a misspelt one.
#include <array>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace atssim::scene {

// Where nodes came from: the scene file, plus the --set overrides (by dotted
// path) so that an error in an overridden value points at the override.
struct YamlSource {
  std::string file;                              // shown in messages
  std::map<std::string, std::string> overrides;  // dotted path -> "key=value" as typed
};

// Text from the scene as a message may quote it: on one line (a newline,
// tab or other control character written as an escape, \n, \x01, …).
std::string one_line(std::string_view text);

class YamlReader {
 public:
  YamlReader(const YAML::Node& node, std::string path, const YamlSource* source)
      : node_(node), path_(std::move(path)), source_(source) {}

  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  bool is_null() const { return !node_ || node_.IsNull(); }

  // "scene.yaml:12" (or "--set a.b=3") for this node.
  std::string where() const;
  int line() const { return node_.Mark().line + 1; }

  // Throws "<where>: <what>; <fix>".
  [[noreturn]] void fail(std::string_view what, std::string_view fix) const;

  // Requires a map whose keys are all in `allowed` (unknown key -> did you mean).
  void expect_map(std::span<const std::string_view> allowed) const;
  // Requires a map; its keys in file order.
  std::vector<std::string> map_keys() const;
  bool has(std::string_view key) const { return node_.IsMap() && node_[std::string(key)]; }
  YamlReader child(std::string_view key) const;
  std::vector<YamlReader> sequence() const;  // requires a sequence

  double number() const;
  int integer() const;
  std::string string() const;
  std::array<double, 3> vec3() const;  // [x, y, z]
  std::array<double, 2> vec2() const;
  std::vector<int> int_list() const;

  // Range-checked conveniences; `range` is the fix text, e.g. "a number > 0".
  double number_in(double lo, double hi, bool lo_open, std::string_view range) const;
  int integer_in(int lo, int hi) const;

 private:
  std::vector<double> numbers(std::size_t expected) const;
  void refuse_text_for(std::string_view kind) const;

  YAML::Node node_;
  std::string path_;
  const YamlSource* source_;
};

}  // namespace atssim::scene
