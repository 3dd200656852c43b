// Which OpenCL C the programs need. The events executor runs the task
// kernels alone; the fused executor appends the dispatcher, which needs
// OpenCL C 2.0 atomics. A device that offers only OpenCL C 1.2 or 3.0
// without the atomic-scope features (NVIDIA's GPUs) can run events, so the
// task kernels must stay OpenCL C 1.2. pocl's compiler enforces the 1.2
// rules (no generic address space, no 2.0 atomics) when asked to.
#include <catch2/catch.hpp>

#include <string>

#include "device/device_set.hpp"
#include "device/device_set_impl.hpp"
#include "device/program_builder.hpp"
#include "solver/method_registry.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

bool builds(const std::string& program, const std::string& options) {
  const auto set = device::DeviceSet::open("cpu");
  try {
    device::build_program(set.impl().contexts.at(0), set.impl().devices, program, options);
    return true;
  } catch (const Error& e) {
    UNSCOPED_INFO(program << " " << options << ": " << std::string(e.what()).substr(0, 400));
    return false;
  }
}

}  // namespace

TEST_CASE("every method's task program builds as OpenCL C 1.2 without the dispatcher, and not with it") {
  REQUIRE_FALSE(solver::methods().empty());
  for (const solver::MethodDescription* m : solver::methods()) {
    const std::string program(m->program);
    INFO(m->name << " (program " << program << ")");
    CHECK(builds(program, "-cl-std=CL1.2 -DATS_FUSED=0 -DATS_TASK_CLOCK=0"));
    // The dispatcher is what needs 2.0: with it the same program fails as
    // 1.2, so the check above tests the task kernels, not a lenient compiler.
    CHECK_FALSE(builds(program, "-cl-std=CL1.2 -DATS_FUSED=1 -DATS_TASK_CLOCK=0"));
  }
}

TEST_CASE("the events executor's hop probe builds as OpenCL C 1.2") { CHECK(builds("noop", "-cl-std=CL1.2")); }
