#include "io/run_header.hpp"

#include <chrono>
#include <sstream>
#include <vector>

#include <fmt/chrono.h>
#include <fmt/format.h>

#ifndef ATSSIM_VERSION
#define ATSSIM_VERSION "0.0.0"
#endif

namespace atssim::io {

std::string now_iso8601() {
  const auto now = std::chrono::system_clock::now();
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(now)));
}

namespace {

void write_devices(hid_t file, const std::vector<DeviceRecord>& devices) {
  H5Handle g = create_group(file, "devices");
  std::vector<std::string> name, vendor, type, platform, version, svm;
  std::vector<int> units, index, sub;
  for (const auto& d : devices) {
    name.push_back(d.name);
    vendor.push_back(d.vendor);
    type.push_back(d.type);
    platform.push_back(d.platform);
    version.push_back(d.version);
    svm.push_back(d.svm);
    units.push_back(d.compute_units);
    index.push_back(d.index);
    sub.push_back(d.sub_device);
  }
  write_string_array(g, "name", name);
  write_string_array(g, "vendor", vendor);
  write_string_array(g, "type", type);
  write_string_array(g, "platform", platform);
  write_string_array(g, "version", version);
  write_string_array(g, "svm", svm);
  write_int_array(g, "compute_units", units, 0);
  write_int_array(g, "index", index, 0);
  write_int_array(g, "sub_device", sub, 0);
}

void write_schedule_info(hid_t file, const ScheduleInfo& info, std::size_t devices) {
  H5Handle g = create_group(file, "schedule");
  write_string_attribute(g, "mode", info.mode);
  write_string_attribute(g, "executor", info.executor);
  write_string_attribute(g, "memory", info.memory);
  H5Handle tasks = create_group(g, "tasks");
  std::vector<std::string> name, kind;
  std::vector<int> iteration, block, part;
  for (const TaskRecord& t : info.tasks) {
    name.push_back(t.name);
    kind.push_back(t.kind);
    iteration.push_back(t.iteration);
    block.push_back(t.block);
    part.push_back(t.part);
  }
  write_string_array(tasks, "name", name);
  write_string_array(tasks, "kind", kind);
  write_int_array(tasks, "iteration", iteration, 0);
  write_int_array(tasks, "block", block, 0);
  write_int_array(tasks, "part", part, 0);
  std::vector<int> from, to;
  for (const auto& [a, b] : info.edges) {
    from.push_back(a);
    to.push_back(b);
  }
  write_int_array(tasks, "edge_from", from, 0);
  write_int_array(tasks, "edge_to", to, 0);
  H5Handle dev = h5_check(H5Gopen2(file, "devices", H5P_DEFAULT), H5Gclose, "/devices");
  if (info.costs.tasks > 0) write_double_array(dev, "costs_ms", info.costs.ms, info.costs.devices);
  if (!info.latency_ms.empty()) write_double_array(dev, "latency_ms", info.latency_ms, devices);
  if (!info.ms_per_byte.empty()) write_double_array(dev, "ms_per_byte", info.ms_per_byte, devices);
  if (!info.split_fractions.empty()) write_double_array(dev, "split_fractions", info.split_fractions, 0);
}

void write_mesh(hid_t file, std::span<const model::ObjectRange> objects) {
  H5Handle mesh = create_group(file, "mesh");
  for (const auto& obj : objects) {
    H5Handle g = create_group(mesh, obj.name);
    std::vector<float> rest;
    for (const auto& p : obj.rest_position) rest.insert(rest.end(), {float(p.x()), float(p.y()), float(p.z())});
    std::vector<int> tris;
    for (const auto& t : obj.triangles) tris.insert(tris.end(), t.begin(), t.end());
    write_float_array(g, "rest_positions", rest, 3);
    write_int_array(g, "triangles", tris, 3);
    write_int_array(g, "pinned", obj.pinned, 0);
    std::vector<int> tets;
    for (const auto& t : obj.tetrahedra) tets.insert(tets.end(), t.begin(), t.end());
    write_int_array(g, "tetrahedra", tets, 4);  // [k, 4]; empty for cloth
    write_int_attribute(g, "vertex_offset", obj.vertex_offset);
    write_int_attribute(g, "vertex_count", obj.vertex_count);
  }
}

}  // namespace

void write_run_header(hid_t file, const RunInfo& info, std::span<const model::ObjectRange> objects) {
  write_string_attribute(file, "format", "atssim");
  write_int_attribute(file, "format_version", kFormatVersion);
  write_string_attribute(file, "atssim_version", ATSSIM_VERSION);
  write_string_attribute(file, "command_line", info.command_line);
  write_string_attribute(file, "created", now_iso8601());
  write_int_attribute(file, "complete", 0);
  write_string_attribute(file, "error", "");

  H5Handle scene = create_group(file, "scene");
  write_string_dataset(scene, "yaml", info.scene_yaml);
  write_string_dataset(scene, "resolved", info.resolved_yaml);
  write_devices(file, info.devices);
  write_schedule_info(file, info.schedule, info.devices.size());
  write_mesh(file, objects);
  create_group(file, "frames");
  create_group(file, "timing");
  {
    H5Handle sched = h5_check(H5Gopen2(file, "schedule", H5P_DEFAULT), H5Gclose, "/schedule");
    create_group(sched, "waits");
    create_group(sched, "makespan");
  }
  create_group(file, "contact");
}

std::string resumable_part(const std::string& resolved) {
  std::string out, line;
  std::istringstream in(resolved);
  while (std::getline(in, line)) {
    const auto key = line.find_first_not_of(' ');
    if (key != std::string::npos && (line.compare(key, 7, "frames:") == 0 || line.compare(key, 5, "path:") == 0 ||
                                     line.compare(key, 7, "strict:") == 0))
      continue;
    out += line + "\n";
  }
  return out;
}

std::string read_string_dataset(hid_t file, const char* name) {
  H5Handle set = h5_check(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose, name);
  H5Handle type = h5_check(H5Dget_type(set), H5Tclose, name);
  std::string value(H5Tget_size(type), '\0');
  h5_check(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.data()), name);
  return value.substr(0, value.find('\0'));
}

}  // namespace atssim::io
