#include "scene/yaml_reader.hpp"

#include <cmath>

#include <fmt/format.h>

#include "util/did_you_mean.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

std::string join(std::span<const std::string_view> words) {
  std::string out;
  for (std::string_view w : words) {
    if (!out.empty()) out += ", ";
    out += w;
  }
  return out;
}

std::string type_name(const YAML::Node& node) {
  if (!node || node.IsNull()) return "nothing";
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a list";
  return fmt::format("'{}'", node.Scalar());
}

}  // namespace

std::string one_line(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out;
}

std::string YamlReader::where() const {
  if (source_ != nullptr) {
    // The longest override that is a prefix of this path produced the node.
    for (auto it = source_->overrides.rbegin(); it != source_->overrides.rend(); ++it) {
      const std::string& p = it->first;
      if (path_ == p || (path_.size() > p.size() && path_.compare(0, p.size(), p) == 0 && (path_[p.size()] == '.'))) {
        return fmt::format("{} (--set {})", source_->file, it->second);
      }
    }
  }
  const std::string file = source_ != nullptr ? source_->file : std::string("<scene>");
  if (node_.Mark().is_null()) return file;
  return fmt::format("{}:{}", file, line());
}

void YamlReader::fail(std::string_view what, std::string_view fix) const {
  throw input_error(fmt::format("{}: {}; {}", where(), one_line(what), fix));
}

void YamlReader::expect_map(std::span<const std::string_view> allowed) const {
  if (!node_.IsMap()) {
    fail(fmt::format("'{}' should be a map of keys, found {}", path_.empty() ? "scene" : path_, type_name(node_)),
         fmt::format("write it as 'key: value' lines (keys: {})", join(allowed)));
  }
  for (const auto& entry : node_) {
    const std::string key = entry.first.as<std::string>();
    bool known = false;
    for (std::string_view a : allowed) known = known || key == a;
    if (known) continue;
    YamlReader at(entry.first, path_.empty() ? key : path_ + "." + key, source_);
    const std::string guess = closest_match(key, allowed);
    if (!guess.empty()) {
      at.fail(fmt::format("unknown key '{}'", key), fmt::format("did you mean '{}'?", guess));
    }
    at.fail(fmt::format("unknown key '{}'", key), fmt::format("allowed here: {}", join(allowed)));
  }
}

std::vector<std::string> YamlReader::map_keys() const {
  if (!node_.IsMap()) {
    fail(fmt::format("'{}' should be a map of keys, found {}", path_.empty() ? "scene" : path_, type_name(node_)),
         "write it as 'key: value' lines");
  }
  std::vector<std::string> keys;
  for (const auto& entry : node_) keys.push_back(entry.first.as<std::string>());
  return keys;
}

YamlReader YamlReader::child(std::string_view key) const {
  const std::string k(key);
  return YamlReader(node_[k], path_.empty() ? k : path_ + "." + k, source_);
}

std::vector<YamlReader> YamlReader::sequence() const {
  if (!node_.IsSequence()) {
    fail(fmt::format("'{}' should be a list, found {}", path_, type_name(node_)),
         "write it as '- item' lines or [a, b, …]");
  }
  std::vector<YamlReader> items;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    items.emplace_back(node_[i], fmt::format("{}.{}", path_, i), source_);
  }
  return items;
}

// A scalar YAML says is text — quoted ("0.2"), a block (|) or tagged !!str —
// where a number belongs: read as a number it would be a silent guess.
void YamlReader::refuse_text_for(std::string_view kind) const {
  if (!node_.IsScalar()) return;
  const std::string& tag = node_.Tag();
  if (tag == "!" || tag == "tag:yaml.org,2002:str") {
    fail(fmt::format("'{}' should be {}, found the text '{}' (quoted or tagged !!str)", path_, kind, node_.Scalar()),
         "write the number without quotes");
  }
}

double YamlReader::number() const {
  refuse_text_for("a number");
  double value = 0.0;
  if (!node_.IsScalar() || !YAML::convert<double>::decode(node_, value)) {
    fail(fmt::format("'{}' should be a number, found {}", path_, type_name(node_)), "write a number such as 0.5");
  }
  if (!std::isfinite(value)) {
    fail(fmt::format("'{}' is {}", path_, node_.Scalar()), "write a finite number");
  }
  return value;
}

int YamlReader::integer() const {
  refuse_text_for("a whole number");
  long long value = 0;
  if (!node_.IsScalar() || !YAML::convert<long long>::decode(node_, value) || value < std::numeric_limits<int>::min() ||
      value > std::numeric_limits<int>::max()) {
    fail(fmt::format("'{}' should be a whole number, found {}", path_, type_name(node_)),
         "write an integer such as 16");
  }
  return static_cast<int>(value);
}

std::string YamlReader::string() const {
  if (!node_.IsScalar()) {
    fail(fmt::format("'{}' should be text, found {}", path_, type_name(node_)), "write a single value");
  }
  return node_.Scalar();
}

std::vector<double> YamlReader::numbers(std::size_t expected) const {
  if (!node_.IsSequence() || node_.size() != expected) {
    fail(fmt::format("'{}' should be a list of {} numbers, found {}", path_, expected, type_name(node_)),
         expected == 3 ? "write it as [x, y, z]" : "write it as [a, b]");
  }
  std::vector<double> out;
  for (const YamlReader& item : sequence()) out.push_back(item.number());
  return out;
}

std::array<double, 3> YamlReader::vec3() const {
  const auto v = numbers(3);
  return {v[0], v[1], v[2]};
}

std::array<double, 2> YamlReader::vec2() const {
  const auto v = numbers(2);
  return {v[0], v[1]};
}

std::vector<int> YamlReader::int_list() const {
  std::vector<int> out;
  for (const YamlReader& item : sequence()) out.push_back(item.integer());
  return out;
}

double YamlReader::number_in(double lo, double hi, bool lo_open, std::string_view range) const {
  const double v = number();
  if ((lo_open ? v <= lo : v < lo) || v > hi) {
    fail(fmt::format("'{}' is {}, out of range", path_, node_.Scalar()), fmt::format("use {}", range));
  }
  return v;
}

int YamlReader::integer_in(int lo, int hi) const {
  const int v = integer();
  if (v < lo || v > hi) {
    fail(fmt::format("'{}' is {}, out of range", path_, v), fmt::format("use a whole number from {} to {}", lo, hi));
  }
  return v;
}

}  // namespace atssim::scene
