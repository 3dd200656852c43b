// What a user meets from each kind of error, through the real binary
// (util/error.hpp): a bug exits 1 and says "internal error"; bad input that a
// later stage finds exits 2 naming the scene's file and line.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

#include "io/result_reader.hpp"
#include "support/cli_runs.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

int lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

// atssim with ATSSIM_TEST_FAULT=fault in its environment (app/simulation.cpp).
test::Outcome run_with_fault(const test::TempDir& dir, const std::string& fault, const std::string& args) {
  ::setenv("ATSSIM_TEST_FAULT", fault.c_str(), 1);
  test::Outcome r = test::run_atssim(dir, args);
  ::unsetenv("ATSSIM_TEST_FAULT");
  return r;
}

}  // namespace

TEST_CASE("a bug in the middle of a run exits 1 with one line saying 'internal error', the frames before it kept") {
  const std::string fault = GENERATE("internal", "exception");  // an atssim::Error of kind internal; a std:: one
  INFO(fault);
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(6));
  const auto r = run_with_fault(dir, fault, "run " + scene + " -o " + dir.file("out.h5") + " --frames 4 --devices cpu");
  INFO(r.err);
  CHECK(r.code == 1);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.rfind("atssim: internal error: ", 0) == 0);
  CHECK(r.err.find("ATSSIM_TEST_FAULT") != std::string::npos);
  CHECK(r.err.find("2 frames kept") != std::string::npos);  // the initial state and frame 1
  const io::ResultSummary s = io::read_summary(dir.file("out.h5"));
  CHECK_FALSE(s.complete);
  CHECK(s.frames == 2);
}

TEST_CASE("bad input that a later stage finds exits 2 naming the scene's file and line, and writes nothing") {
  // The device stage never sees the scene: the scene line comes from the
  // error's Setting, not from its text.
  test::TempDir dir;
  const std::string scene = dir.write("cloth.yaml", test::hanging_cloth_yaml(6) + "devices: tpu\n");
  const auto r = test::run_atssim(dir, "run " + scene + " -o " + dir.file("out.h5") + " --frames 2");
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.rfind("atssim: " + scene + ":10: devices 'tpu': ", 0) == 0);
  CHECK(r.err.find("internal error") == std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("out.h5")));
}
