#include "scene/yaml_document.hpp"

#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>

#include "util/error.hpp"

namespace atssim::scene {

namespace {

// Where a document starts and where its root node is; the rest is ignored.
class DocumentMarks : public YAML::EventHandler {
 public:
  YAML::Mark start;
  YAML::Mark root;

  void OnDocumentStart(const YAML::Mark& mark) override {
    start = mark;
    root = YAML::Mark::null_mark();
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override { node(mark); }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnMapEnd() override {}

 private:
  void node(const YAML::Mark& mark) {
    if (root.is_null()) root = mark;
  }
};

}  // namespace

YAML::Node load_one_document(const std::string& yaml_text, const std::string& source_name) {
  std::istringstream in(yaml_text);
  YAML::Parser parser(in);
  DocumentMarks marks;
  // Up to three documents: a third that starts where the second did means
  // the parser did not move on (the ','), not that there are three.
  int documents = 0;
  int second_start = -1;
  int second_line = 0;
  while (documents < 3 && parser.HandleNextDocument(marks)) {
    if (++documents == 2) {
      second_start = marks.start.pos;
      second_line = (marks.root.is_null() ? marks.start : marks.root).line + 1;
    }
  }
  if (documents == 3 && marks.start.pos == second_start) {
    throw input_error(
        fmt::format("{}:{}: YAML syntax error: a ',' outside brackets, where a key or a value must start; remove it",
                    source_name, marks.start.line + 1));
  }
  if (documents >= 2) {
    throw input_error(fmt::format(
        "{}:{}: a second YAML document ('---') in the scene file; a scene is one document: remove the '---' line "
        "and merge the keys, or split the file",
        source_name, second_line));
  }
  return documents == 0 ? YAML::Node() : YAML::Load(yaml_text);
}

}  // namespace atssim::scene
