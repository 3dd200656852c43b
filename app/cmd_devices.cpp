// `atssim devices`: every OpenCL platform and device atssim can use.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "device/device_info.hpp"
#include "util/error.hpp"

namespace atssim::app {

Action add_devices_command(CLI::App& cli) {
  CLI::App* cmd = cli.add_subcommand("devices", "List OpenCL devices: type, compute units, OpenCL version, SVM");
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json, "Print JSON");
  return [json]() {
    const auto devices = device::list_devices();
    if (devices.empty()) {
      throw input_error(
          "no OpenCL platform with a device found: install an OpenCL driver (on Debian: pocl-opencl-icd, "
          "scripts/setup.sh installs it), and check OCL_ICD_VENDORS if it is set");
    }
    if (*json) {
      fmt::print("[\n");
      for (std::size_t i = 0; i < devices.size(); ++i) {
        const auto& d = devices[i];
        fmt::print(
            "  {{\"index\": {}, \"name\": \"{}\", \"platform\": \"{}\", \"vendor\": \"{}\", \"type\": \"{}\", "
            "\"compute_units\": {}, \"version\": \"{}\", \"c_version\": \"{}\", \"svm\": \"{}\", "
            "\"max_sub_devices\": {}}}{}\n",
            d.index, d.name, d.platform, d.vendor, d.type, d.compute_units, d.version, d.c_version, svm_text(d.svm),
            d.max_sub_devices, i + 1 < devices.size() ? "," : "");
      }
      fmt::print("]\n");
      return 0;
    }
    for (const auto& d : devices) fmt::print("{}\n", describe(d));
    fmt::print(
        "\n--devices takes: default, cpu, gpu, cpu/2 (a device split into sub-devices), indices (0,1) or "
        "platform:device pairs (0:0,1:0) as shown in parentheses. Devices of different platforms share no "
        "memory; --memory separate makes devices of one platform work the same way.\n");
    return 0;
  };
}

}  // namespace atssim::app
