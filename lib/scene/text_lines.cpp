#include "scene/text_lines.hpp"

#include <charconv>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "scene/input_file.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

}  // namespace

TextLines::TextLines(std::string path, bool hash_comments) : path_(std::move(path)), hash_comments_(hash_comments) {
  check_input_file(path_, "mesh file", "", kMaxMeshBytes);
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw input_error(fmt::format("{}: cannot be read; check that it exists and is readable", path_));
  for (std::string l; std::getline(in, l);) lines_.push_back(std::move(l));
}

std::string_view TextLines::text() const {
  if (line_ == 0 || static_cast<std::size_t>(line_) > lines_.size()) return {};
  std::string_view l = lines_[line_ - 1];
  if (hash_comments_) l = l.substr(0, l.find('#'));
  return l;
}

bool TextLines::next() {
  while (next_index_ < lines_.size()) {
    line_ = static_cast<int>(++next_index_);
    const std::string_view l = text();
    tokens_.clear();
    std::size_t i = 0;
    while (i < l.size()) {
      while (i < l.size() && is_space(l[i])) ++i;
      const std::size_t start = i;
      while (i < l.size() && !is_space(l[i])) ++i;
      if (i > start) tokens_.push_back(l.substr(start, i - start));
    }
    if (!tokens_.empty()) return true;
  }
  tokens_.clear();
  return false;
}

void TextLines::expect_next(std::string_view expected) {
  if (!next()) {
    line_ = static_cast<int>(lines_.size());
    fail(fmt::format("the file ends where {} was expected", expected), "the file is truncated; export it again");
  }
}

void TextLines::require(std::size_t n, std::string_view layout) const {
  if (tokens_.size() < n) {
    fail(fmt::format("expected {} values, found {}", n, tokens_.size()),
         fmt::format("the line should read '{}'", layout));
  }
}

double TextLines::number(std::size_t i, std::string_view what) const {
  double v = 0.0;
  std::string_view t = tokens_.at(i);
  if (t.size() > 1 && t[0] == '+') t.remove_prefix(1);  // from_chars rejects an explicit '+'
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v)) {
    fail(fmt::format("{} is '{}', not a number", what, t), "write a finite decimal number");
  }
  return v;
}

long long TextLines::integer(std::size_t i, std::string_view what) const {
  long long v = 0;
  const std::string_view t = tokens_.at(i);
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size()) {
    fail(fmt::format("{} is '{}', not a whole number", what, t), "write an integer");
  }
  return v;
}

void TextLines::fail(std::string_view what, std::string_view fix) const {
  // An empty file has no line to name.
  if (line_ <= 0) throw input_error(fmt::format("{}: {} (the file is empty); {}", path_, what, fix));
  throw input_error(fmt::format("{}:{}: {}; {}", path_, line_, what, fix));
}

}  // namespace atssim::scene
