#pragma once
// Running the atssim binary (ATSSIM_BINARY, set by the test's CMake target)
// with its stdout and stderr captured: for tests of what a user sees.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "support/temp_dir.hpp"

namespace atssim::test {

struct Outcome {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs atssim with `args` (a shell fragment) in no terminal, capturing
// stdout and stderr into files of `dir`.
inline Outcome run_atssim(const TempDir& dir, const std::string& args) {
  const std::string cmd =
      std::string(ATSSIM_BINARY) + " " + args + " >" + dir.file("stdout") + " 2>" + dir.file("stderr") + " </dev/null";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir.file("stdout")), slurp(dir.file("stderr"))};
}

}  // namespace atssim::test
