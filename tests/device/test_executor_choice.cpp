#include <catch2/catch.hpp>

#include "device/executor_choice.hpp"
#include "util/error.hpp"

using namespace atssim;
using device::ExecutorKind;

namespace {

device::DeviceInfo with_svm(bool fine, bool atomics, std::string name = "dev") {
  device::DeviceInfo d;
  d.name = std::move(name);
  d.index = 3;
  d.svm.coarse_buffer = true;
  d.svm.fine_buffer = fine;
  d.svm.atomics = atomics;
  return d;
}

}  // namespace

TEST_CASE("auto runs fused exactly when every device has fine-grain buffer SVM with atomics") {
  const std::vector<device::DeviceInfo> both{with_svm(true, true), with_svm(true, true)};
  CHECK(device::choose_executor(ExecutorKind::automatic, both) == ExecutorKind::fused);
  const std::vector<device::DeviceInfo> one_coarse{with_svm(true, true), with_svm(false, false)};
  CHECK(device::choose_executor(ExecutorKind::automatic, one_coarse) == ExecutorKind::events);
  const std::vector<device::DeviceInfo> no_atomics{with_svm(true, false)};
  CHECK(device::choose_executor(ExecutorKind::automatic, no_atomics) == ExecutorKind::events);
  CHECK(device::choose_executor(ExecutorKind::automatic, {}) == ExecutorKind::events);
}

TEST_CASE("events stays events, and fused where a device cannot is an input error naming it") {
  const std::vector<device::DeviceInfo> both{with_svm(true, true), with_svm(true, true)};
  CHECK(device::choose_executor(ExecutorKind::events, both) == ExecutorKind::events);
  CHECK(device::choose_executor(ExecutorKind::fused, both) == ExecutorKind::fused);
  const std::vector<device::DeviceInfo> coarse{with_svm(true, true), with_svm(false, true, "old gpu")};
  try {
    device::choose_executor(ExecutorKind::fused, coarse);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    CHECK(std::string(e.what()).find("device 3 (old gpu) has no fine-grain buffer SVM") != std::string::npos);
  }
}

TEST_CASE("executor names parse, and an unknown one lists the choices") {
  CHECK(device::parse_executor_kind("auto") == ExecutorKind::automatic);
  CHECK(device::parse_executor_kind("fused") == ExecutorKind::fused);
  CHECK(device::parse_executor_kind("events") == ExecutorKind::events);
  CHECK_THROWS_WITH(device::parse_executor_kind("fast"), Catch::Contains("use auto") && Catch::Contains("events"));
}

TEST_CASE("devices with memories of their own run events, and fused there is an input error") {
  const std::vector<device::DeviceInfo> both{with_svm(true, true), with_svm(true, true)};
  CHECK(device::choose_executor(ExecutorKind::automatic, both, 2) == ExecutorKind::events);
  CHECK_THROWS_WITH(device::choose_executor(ExecutorKind::fused, both, 2), Catch::Contains("2 memories"));
}
