#pragma once
// A scene file's one YAML document. yaml-cpp 0.7's LoadAll never returns on
// a ',' outside brackets where a node should start (each call hands back an
// empty document without reading on, and the list grows until memory runs
// out), so the documents are walked with its event parser first.
#include <string>

#include <yaml-cpp/yaml.h>

namespace atssim::scene {

// The scene's root node (null for an empty file). Throws an input error
// naming the line of a second document ('---') or of a ',' the parser cannot
// read past; yaml-cpp's ParserException for any other syntax error.
YAML::Node load_one_document(const std::string& yaml_text, const std::string& source_name);

}  // namespace atssim::scene
