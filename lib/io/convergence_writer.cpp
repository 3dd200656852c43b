#include "io/convergence_writer.hpp"

#include <fmt/format.h>

#include "io/h5_handle.hpp"
#include "util/error.hpp"

#ifndef ATSSIM_VERSION
#define ATSSIM_VERSION "0.0.0"
#endif

namespace atssim::io {

void write_convergence(const std::string& path, const ConvergenceResult& r) {
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) {
    throw input_error(
        fmt::format("cannot create output file '{}': check that its folder exists and is writable", path));
  }
  H5Handle file(id, H5Fclose);
  write_string_attribute(file, "format", "atssim");
  write_int_attribute(file, "format_version", 1);
  write_string_attribute(file, "atssim_version", ATSSIM_VERSION);
  write_string_attribute(file, "command_line", r.command_line);
  write_int_attribute(file, "complete", 1);
  H5Handle scene = create_group(file, "scene");
  write_string_dataset(scene, "yaml", r.scene_yaml);
  write_string_dataset(scene, "resolved", r.resolved_yaml);
  H5Handle c = create_group(file, "convergence");
  write_int_attribute(c, "frames_before", r.frames_before);
  write_string_attribute(c, "newton_status", r.newton_status);
  write_string_attribute(c, "from", r.from);
  write_int_attribute(c, "newton_iterations", r.newton_iterations);
  const double scalars[] = {r.substep_dt, r.energy_start, r.energy_reference, r.newton_relative_gradient, r.y_floor};
  write_double_array(c, "substep_dt", std::span<const double>(scalars, 1), 0);
  write_double_array(c, "energy_start", std::span<const double>(scalars + 1, 1), 0);
  write_double_array(c, "energy_reference", std::span<const double>(scalars + 2, 1), 0);
  write_double_array(c, "newton_relative_gradient", std::span<const double>(scalars + 3, 1), 0);
  write_double_array(c, "y_floor", std::span<const double>(scalars + 4, 1), 0);
  std::vector<std::string> names;
  for (const auto& t : r.traces) names.push_back(t.variant);
  write_string_array(c, "variants", names);
  for (const auto& t : r.traces) {
    std::string group = t.variant;
    for (char& ch : group) {
      if (ch == '/') ch = ':';
    }
    H5Handle g = create_group(c, group);
    write_string_attribute(g, "variant", t.variant);
    write_int_array(g, "iterations", t.iterations, 0);
    write_double_array(g, "energy", t.energy, 0);
    write_double_array(g, "relative_error", t.relative_error, 0);
    write_double_array(g, "time_ms", t.time_ms, 0);
  }
}

}  // namespace atssim::io
