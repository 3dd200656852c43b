#pragma once
// Checks every map of a loaded YAML document before anything reads it:
// yaml-cpp keeps the first of two equal keys silently and turns a complex
// key ("? [a, b]: 1") into an exception deep in a conversion. Both become
// one line naming the file and line.
#include <string>

#include <yaml-cpp/yaml.h>

namespace atssim::scene {

// Throws atssim::Error (input) "<file>:<line>: …; …" for a duplicate key
// (naming the line of the first one), a key that is not plain text, and a
// document whose root is not a map.
void check_yaml_keys(const YAML::Node& root, const std::string& file);

// The same checks (tags, merge keys, duplicates, nesting) of a value given on
// the command line; messages start with `where` ("--set key=value").
void check_yaml_value(const YAML::Node& value, const std::string& where);

}  // namespace atssim::scene
