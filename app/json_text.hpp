#pragma once
// Small pieces of JSON text for the subcommands' --json output.
#include <string>
#include <vector>

namespace atssim::app {

// A JSON string literal, quotes included.
std::string json_string(const std::string& text);
// A JSON number; NaN and infinities become null (JSON has neither).
std::string json_number(double value);
// "[a, b, …]" of already-formatted JSON values.
std::string json_array(const std::vector<std::string>& values);

}  // namespace atssim::app
