#include <catch2/catch.hpp>

#include "device/device_info.hpp"
#include "device/device_set.hpp"
#include "util/error.hpp"

using namespace atssim;

TEST_CASE("the machine offers at least one OpenCL device with SVM") {
  const auto devices = device::list_devices();
  REQUIRE_FALSE(devices.empty());
  bool svm = false;
  for (const auto& d : devices) svm = svm || d.svm.coarse_buffer;
  CHECK(svm);
}

TEST_CASE("the CPU device splits into two 1-CU sub-devices sharing one context") {
  const auto set = device::DeviceSet::open("cpu/2");
  REQUIRE(set.size() == 2);
  CHECK(set.info(0).sub_device == 0);
  CHECK(set.info(1).sub_device == 1);
  CHECK(set.info(0).compute_units == set.info(1).compute_units);
}

TEST_CASE("a device spec that matches nothing is an input error listing the devices") {
  for (const char* spec : {"gpu7", "99", "cpu/x", "cpu/64", "banana"}) {
    try {
      device::DeviceSet::open(spec);
      FAIL("expected an error for " << spec);
    } catch (const Error& e) {
      const std::string msg = e.what();
      CHECK(e.exit_code() == 2);
      CHECK(msg.find("available:") != std::string::npos);
      CHECK(msg.find('\n') == std::string::npos);
    }
  }
}
