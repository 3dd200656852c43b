#pragma once
// The devices a run uses, one in-order profiling queue each. The devices of
// one platform share one OpenCL context and its SVM; devices of different
// platforms (a vendor GPU beside pocl's CPU) get a context each, and so does
// every device when the set is opened with separate memories. Chosen by a
// spec string:
//   default      best GPU + a CPU of the same platform; only a CPU: that one
//   cpu | gpu    first device of that type
//   N            device N of `atssim devices`
//   P:D          device D of platform P (the numbers `atssim devices` prints)
//   SEL/K        the selected device split into K equal sub-devices ("cpu/2")
//   SEL/K:i      only sub-device i of them ("cpu/2:1")
//   A,B          several selections
#include <memory>
#include <string>
#include <vector>

#include "device/device_info.hpp"

namespace atssim::device {

enum class MemoryMode {
  shared,    // one context per platform: its devices share SVM
  separate,  // one context per device, even on one platform (tests the copy path)
};

MemoryMode parse_memory_mode(const std::string& text);  // "shared" | "separate"; else an input error

class DeviceSet {
 public:
  // Contexts are opened once per spec and process, and kept until exit:
  // tearing a pocl 3.1 context down while its worker threads still finish
  // event bookkeeping crashed now and then; a run opens one set anyway.
  // Throws atssim::Error: input (exit 2) when the spec is malformed or
  // matches nothing, listing the devices, or when there is no OpenCL device
  // at all; runtime (exit 1) when a device lacks SVM.
  static DeviceSet open(const std::string& spec, MemoryMode memory = MemoryMode::shared);

  DeviceSet(DeviceSet&&) noexcept;
  DeviceSet& operator=(DeviceSet&&) noexcept;
  ~DeviceSet();

  std::size_t size() const;
  const DeviceInfo& info(std::size_t i) const;
  const std::vector<DeviceInfo>& infos() const;
  // Fine-grain buffer SVM on every device of the set.
  bool fine_grain_svm() const;
  // Memories (contexts) and the one a device uses.
  std::size_t memories() const;
  std::size_t memory_of(std::size_t device) const;

  struct Impl;
  Impl& impl() const { return *impl_; }

 private:
  explicit DeviceSet(std::shared_ptr<Impl> impl);
  std::shared_ptr<Impl> impl_;
};

}  // namespace atssim::device
