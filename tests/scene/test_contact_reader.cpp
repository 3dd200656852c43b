// The scene's `contact:` map (lib/scene/contact_reader): the strict key,
// its default and its way through the resolved YAML; a bad value names the
// line (the bad-input suite runs it through the binary too).
#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_loader.hpp"
#include "scene/scene_yaml.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

std::string scene_with(const std::string& contact) {
  return "simulation: {fps: 60, substeps: 2, iterations: 2, frames: 2}\n"
         "objects:\n"
         "  - {name: cloth, grid: {size: [1, 1], resolution: [8, 8]}, material: {density: 0.2, stretch_stiffness: "
         "1000}}\n" +
         contact;
}

}  // namespace

TEST_CASE("contact.strict is false unless set, and the resolved scene keeps it", "[scene][contact]") {
  const auto off = scene::parse_scene(scene_with("contact: {self: true}\n"), "s.yaml", ".");
  CHECK_FALSE(off.contact.strict);
  CHECK(off.resolved_yaml.find("strict: false") != std::string::npos);
  const auto on = scene::parse_scene(scene_with("contact: {self: true, strict: true}\n"), "s.yaml", ".");
  CHECK(on.contact.strict);
  const auto again = scene::parse_scene(on.resolved_yaml, "resolved.yaml", ".");
  CHECK(again.contact.strict);
  CHECK(again.contact.enabled);
  const auto set = scene::parse_scene(scene_with("contact: {self: true}\n"), "s.yaml", ".",
                                      std::vector<std::string>{"contact.strict=true"});
  CHECK(set.contact.strict);
}

TEST_CASE("contact.strict that is not true or false names its line", "[scene][contact]") {
  try {
    scene::parse_scene(scene_with("contact:\n  self: true\n  strict: 1\n"), "s.yaml", ".");
    FAIL("accepted strict: 1");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::input);
    CHECK(std::string(e.what()).find("s.yaml:6:") != std::string::npos);
    CHECK(std::string(e.what()).find("use true or false") != std::string::npos);
  }
}
