#include "device/device_set.hpp"

#include <algorithm>
#include <map>
#include <mutex>
#include <sstream>

#include <fmt/format.h>

#include "device/device_query.hpp"
#include "device/device_set_impl.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

std::string available(const std::vector<DeviceHandle>& all) {
  std::string s;
  for (const auto& h : all) {
    s += fmt::format("{}{}: {} ({}, {} CUs{})", s.empty() ? "" : "; ", h.info.index, h.info.name, h.info.type,
                     h.info.compute_units,
                     h.info.max_sub_devices >= 2 ? fmt::format(", /{} ok", h.info.max_sub_devices) : "");
  }
  return s;
}

// The flag's name leads; where the spec came from a scene line, the caller
// puts that line in its place (Setting::devices, app/scene_checks).
[[noreturn]] void bad_spec(const std::string& spec, const std::string& why, const std::vector<DeviceHandle>& all) {
  const std::string detail = fmt::format("'{}': {}; available: {} (e.g. --devices cpu, --devices 0, --devices cpu/2)",
                                         spec, why, available(all));
  throw Error("--devices " + detail, Setting::devices, detail);
}

std::vector<const DeviceHandle*> pick(const std::string& selector, const std::string& spec,
                                      const std::vector<DeviceHandle>& all) {
  auto first_of = [&](const char* type) -> const DeviceHandle* {
    const DeviceHandle* best = nullptr;
    for (const auto& h : all) {
      if (h.info.type == type && (best == nullptr || h.info.compute_units > best->info.compute_units)) best = &h;
    }
    return best;
  };
  if (selector == "default") {
    const DeviceHandle* gpu = first_of("gpu");
    if (gpu == nullptr) {
      const DeviceHandle* cpu = first_of("cpu");
      return {cpu != nullptr ? cpu : &all.front()};
    }
    for (const auto& h : all) {
      if (h.info.type == "cpu" && h.info.platform_index == gpu->info.platform_index) return {gpu, &h};
    }
    return {gpu};
  }
  if (selector == "cpu" || selector == "gpu") {
    const DeviceHandle* h = first_of(selector.c_str());
    if (h == nullptr) bad_spec(spec, fmt::format("no {} device", selector), all);
    return {h};
  }
  const auto is_number = [](const std::string& t) {
    return !t.empty() && t.size() < 9 && std::all_of(t.begin(), t.end(), ::isdigit);
  };
  if (is_number(selector)) {
    const std::size_t index = std::stoul(selector);
    if (index >= all.size()) bad_spec(spec, fmt::format("there is no device {}", index), all);
    return {&all[index]};
  }
  if (const auto colon = selector.find(':'); colon != std::string::npos) {
    const std::string p = selector.substr(0, colon), d = selector.substr(colon + 1);
    if (is_number(p) && is_number(d)) {
      for (const auto& h : all) {
        if (h.info.platform_index == std::stoi(p) && h.info.platform_device == std::stoi(d)) return {&h};
      }
      const bool platform_known =
          std::any_of(all.begin(), all.end(), [&](const auto& h) { return h.info.platform_index == std::stoi(p); });
      bad_spec(spec,
               platform_known ? fmt::format("platform {} has no device {}", p, d)
                              : fmt::format("there is no OpenCL platform {}", p),
               all);
    }
  }
  bad_spec(spec, fmt::format("'{}' is not a device", selector), all);
}

}  // namespace

DeviceSet::DeviceSet(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}
DeviceSet::DeviceSet(DeviceSet&&) noexcept = default;
DeviceSet& DeviceSet::operator=(DeviceSet&&) noexcept = default;
DeviceSet::~DeviceSet() = default;

std::size_t DeviceSet::size() const { return impl_->devices.size(); }
const DeviceInfo& DeviceSet::info(std::size_t i) const { return impl_->infos.at(i); }
const std::vector<DeviceInfo>& DeviceSet::infos() const { return impl_->infos; }
std::size_t DeviceSet::memories() const { return impl_->contexts.size(); }
std::size_t DeviceSet::memory_of(std::size_t device) const { return impl_->memory_of.at(device); }
bool DeviceSet::fine_grain_svm() const {
  return std::all_of(impl_->infos.begin(), impl_->infos.end(), [](const DeviceInfo& d) { return d.svm.fine_buffer; });
}

namespace {

std::shared_ptr<DeviceSet::Impl> open_impl(const std::string& spec_in, MemoryMode memory);

}  // namespace

MemoryMode parse_memory_mode(const std::string& text) {
  if (text == "shared") return MemoryMode::shared;
  if (text == "separate") return MemoryMode::separate;
  throw input_error(
      fmt::format("unknown memory mode '{}'; use shared (the devices of one platform share SVM) or "
                  "separate (every device its own memory, copies through the host)",
                  text));
}

DeviceSet DeviceSet::open(const std::string& spec_in, MemoryMode memory) {
  // Leaked on purpose: never destroyed, so never torn down (see the header).
  static auto* cache = new std::map<std::pair<std::string, MemoryMode>, std::shared_ptr<Impl>>();
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  const std::string spec = spec_in.empty() ? "default" : spec_in;
  auto it = cache->find({spec, memory});
  if (it == cache->end()) it = cache->emplace(std::make_pair(spec, memory), open_impl(spec, memory)).first;
  return DeviceSet(it->second);
}

namespace {

std::shared_ptr<DeviceSet::Impl> open_impl(const std::string& spec_in, MemoryMode memory) {
  const std::vector<DeviceHandle> all = all_device_handles();
  if (all.empty()) {
    // The machine's set-up, not a failed run: one line and exit 2, like any input to fix.
    throw input_error(
        "no OpenCL platform with a device found: install an OpenCL driver (on Debian: pocl-opencl-icd, "
        "scripts/setup.sh installs it), check OCL_ICD_VENDORS if it is set, and run `atssim devices`");
  }
  const std::string spec = spec_in.empty() ? "default" : spec_in;
  auto impl = std::make_shared<DeviceSet::Impl>();
  std::stringstream items(spec);
  for (std::string item; std::getline(items, item, ',');) {
    std::string selector = item;
    int split = 0;
    int only = -1;  // "cpu/2:1": just sub-device 1 of the two
    // "SEL/K:i" (a sub-device); a "P:D" without '/' is a platform and device.
    if (const auto colon = item.rfind(':'), slash = item.find('/');
        colon != std::string::npos && slash != std::string::npos && colon > slash) {
      const std::string index = item.substr(colon + 1);
      if (index.empty() || index.size() > 6 || !std::all_of(index.begin(), index.end(), ::isdigit)) {
        bad_spec(spec, fmt::format("'{}' must end in a sub-device index (0 … 999999), as in cpu/2:1", item), all);
      }
      only = std::stoi(index);
      item = item.substr(0, colon);
      selector = item;
    }
    if (const auto slash = item.find('/'); slash != std::string::npos) {
      selector = item.substr(0, slash);
      const std::string count = item.substr(slash + 1);
      if (count.empty() || count.size() > 6 || !std::all_of(count.begin(), count.end(), ::isdigit) ||
          std::stoi(count) < 2) {
        bad_spec(spec,
                 fmt::format("'{}' must be followed by a sub-device count from 2 to 999999, as in cpu/2", selector),
                 all);
      }
      split = std::stoi(count);
    }
    if (only >= 0 && (split == 0 || only >= split)) {
      bad_spec(spec,
               fmt::format("'{}:{}' names no sub-device; split first, as in cpu/2:{}", item, only,
                           split > 0 ? split - 1 : 1),
               all);
    }
    for (const DeviceHandle* h : pick(selector, spec, all)) {
      if (split == 0) {
        impl->devices.push_back(h->device);
        impl->infos.push_back(h->info);
        continue;
      }
      if (h->info.max_sub_devices < split || h->info.compute_units < split) {
        bad_spec(spec,
                 fmt::format("device {} ({} compute units) cannot be split into {}", h->info.index,
                             h->info.compute_units, split),
                 all);
      }
      const cl_device_partition_property props[] = {
          CL_DEVICE_PARTITION_EQUALLY, static_cast<cl_device_partition_property>(h->info.compute_units / split), 0};
      std::vector<cl::Device> subs;
      try {
        cl::Device parent = h->device;
        parent.createSubDevices(props, &subs);
      } catch (const cl::Error& e) {
        throw runtime_error(
            fmt::format("splitting device {} into {}: {}", h->info.index, split, cl_error_name(e.err())));
      }
      for (int s = 0; s < split && s < static_cast<int>(subs.size()); ++s) {
        if (only >= 0 && s != only) continue;
        DeviceInfo info = query_info(subs[s], h->info.index, h->info.platform_index, h->info.platform);
        info.sub_device = s;
        info.sub_device_count = split;
        impl->devices.push_back(subs[s]);
        impl->infos.push_back(info);
      }
    }
  }
  if (impl->devices.empty()) bad_spec(spec, "it selects no device", all);
  for (const DeviceInfo& d : impl->infos) {
    if (!d.svm.coarse_buffer && !d.svm.fine_buffer) {
      throw runtime_error(
          fmt::format("device {} ({}) has no shared virtual memory (SVM); atssim needs OpenCL 2.0+ "
                      "SVM — pick another device with --devices (see `atssim devices`)",
                      d.index, d.name));
    }
  }
  // One context per platform (its devices share SVM), or per device.
  std::vector<int> context_key;  // platform index, or device position with separate memories
  for (std::size_t d = 0; d < impl->devices.size(); ++d) {
    const int key = memory == MemoryMode::separate ? static_cast<int>(d) : impl->infos[d].platform_index;
    auto at = std::find(context_key.begin(), context_key.end(), key);
    if (at == context_key.end()) {
      context_key.push_back(key);
      at = context_key.end() - 1;
    }
    impl->memory_of.push_back(static_cast<std::size_t>(at - context_key.begin()));
  }
  if (context_key.size() > 1) {
    // Copies go between whole memories: a memory shared by two devices
    // beside another memory is not supported (use one device per platform).
    for (std::size_t c = 0; c < context_key.size(); ++c) {
      if (impl->devices_of(c).size() > 1) {
        bad_spec(spec,
                 "with devices of several platforms (or separate memories) each platform may contribute one "
                 "device; select one device per platform, e.g. --devices 0:0,1:0",
                 all);
      }
    }
  }
  try {
    for (std::size_t c = 0; c < context_key.size(); ++c) impl->contexts.emplace_back(impl->devices_of(c));
    for (std::size_t d = 0; d < impl->devices.size(); ++d) {
      impl->queues.emplace_back(impl->context_of(d), impl->devices[d], CL_QUEUE_PROFILING_ENABLE);
    }
  } catch (const cl::Error& e) {
    throw runtime_error(fmt::format("creating the OpenCL context: {} in {}", cl_error_name(e.err()), e.what()));
  }
  return impl;
}

}  // namespace

}  // namespace atssim::device
