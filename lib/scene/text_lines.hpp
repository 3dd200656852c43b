#pragma once
// Line-by-line tokenizer for the ASCII mesh formats (TetGen, Gmsh). Every
// error it raises names the file and the line: "box.msh:123: what; fix".
#include <string>
#include <string_view>
#include <vector>

namespace atssim::scene {

class TextLines {
 public:
  // Reads the whole file; `hash_comments` drops everything after '#' (TetGen).
  // Throws atssim::Error (input) when the file cannot be read.
  TextLines(std::string path, bool hash_comments);

  // Moves to the next line that has tokens; false at the end of the file.
  bool next();
  // Like next(), but the end of the file is an error that says what was expected.
  void expect_next(std::string_view expected);

  const std::vector<std::string_view>& tokens() const { return tokens_; }
  std::size_t size() const { return tokens_.size(); }
  std::string_view token(std::size_t i) const { return tokens_[i]; }
  std::string_view text() const;  // the current line, without its comment
  int line() const { return line_; }
  const std::string& path() const { return path_; }

  // The current line must have at least `n` tokens; `layout` shows the expected layout.
  void require(std::size_t n, std::string_view layout) const;
  // Token i as a number; `what` names it in the error ("x coordinate of node 5").
  double number(std::size_t i, std::string_view what) const;
  long long integer(std::size_t i, std::string_view what) const;

  // Throws "<path>:<line>: <what>; <fix>".
  [[noreturn]] void fail(std::string_view what, std::string_view fix) const;

 private:
  std::string path_;
  bool hash_comments_;
  std::vector<std::string> lines_;
  std::size_t next_index_ = 0;
  int line_ = 0;
  std::vector<std::string_view> tokens_;
};

}  // namespace atssim::scene
