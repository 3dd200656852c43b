// libFuzzer harness for the scene parser (scripts/fuzz_scene.sh builds and
// runs it; docs/reliability.md has the runs). Any input must end in a scene
// or in atssim::Error (input): another exception, a crash, a sanitizer
// report, a leak or a hang is a bug. A first line "#set KEY=VALUE" is also
// applied as a --set override, so overrides are fuzzed too.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "scene/scene_loader.hpp"
#include "util/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> overrides;
  if (text.rfind("#set ", 0) == 0) overrides.push_back(text.substr(5, text.find('\n') - 5));
  try {
    // Mesh paths resolve under a folder that does not exist: the fuzzer
    // exercises the parser, not assimp.
    (void)atssim::scene::parse_scene(text, "fuzz.yaml", "/nonexistent-atssim-fuzz", overrides);
  } catch (const atssim::Error& e) {
    if (e.kind() != atssim::ErrorKind::input) {
      std::fprintf(stderr, "%s error from the parser: %s\n",
                   e.kind() == atssim::ErrorKind::internal ? "internal" : "runtime", e.what());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error (not atssim::Error): %s\n", e.what());
    std::abort();
  }
  return 0;
}
