#include "io/xdmf_views.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "io/h5_handle.hpp"

namespace atssim::io {

namespace {

// /xdmf/frames/<k>: a virtual dataset mapping frame k of /frames/positions
// (same file, "."), which grows as frames are appended.
void write_frame_view(hid_t group, std::size_t frame, std::size_t particles) {
  const hsize_t view_dims[2] = {particles, 3};
  H5Handle view = h5_check(H5Screate_simple(2, view_dims, nullptr), H5Sclose, "frame view space");
  const hsize_t src_dims[3] = {frame + 1, particles, 3};
  const hsize_t src_max[3] = {H5S_UNLIMITED, particles, 3};
  H5Handle source = h5_check(H5Screate_simple(3, src_dims, src_max), H5Sclose, "frame view source");
  const hsize_t start[3] = {frame, 0, 0}, count[3] = {1, particles, 3};
  h5_check(H5Sselect_hyperslab(source, H5S_SELECT_SET, start, nullptr, count, nullptr), "frame view selection");
  H5Handle props = h5_check(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "frame view properties");
  h5_check(H5Pset_virtual(props, view, ".", "/frames/positions", source), "frame view mapping");
  const std::string name = std::to_string(frame);
  h5_check(H5Dcreate2(group, name.c_str(), H5T_IEEE_F32LE, view, H5P_DEFAULT, props, H5P_DEFAULT), H5Dclose,
           "creating /xdmf/frames/" + name);
}

}  // namespace

XdmfViews write_xdmf_cells(hid_t file, std::span<const model::ObjectRange> objects, std::size_t particles) {
  XdmfViews views;
  views.particles = particles;
  std::vector<int> cells, cell_object;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const model::ObjectRange& obj = objects[k];
    for (const auto& t : obj.triangles) {
      cells.insert(cells.end(),
                   {kXdmfTriangle, t[0] + obj.vertex_offset, t[1] + obj.vertex_offset, t[2] + obj.vertex_offset});
      cell_object.push_back(static_cast<int>(k));
    }
    for (const auto& t : obj.tetrahedra) {
      cells.insert(cells.end(), {kXdmfTetrahedron, t[0] + obj.vertex_offset, t[1] + obj.vertex_offset,
                                 t[2] + obj.vertex_offset, t[3] + obj.vertex_offset});
      cell_object.push_back(static_cast<int>(k));
    }
  }
  views.cells = cell_object.size();
  views.cell_values = cells.size();
  H5Handle group = create_group(file, "xdmf");
  write_int_array(group, "cells", cells, 0);
  write_int_array(group, "cell_object", cell_object, 0);
  create_group(group, "frames");
  return views;
}

void write_frame_views(hid_t file, XdmfViews& views, std::size_t frames) {
  H5Handle group = h5_check(H5Gopen2(file, "xdmf/frames", H5P_DEFAULT), H5Gclose, "/xdmf/frames");
  for (std::size_t f = views.frames; f < frames; ++f) write_frame_view(group, f, views.particles);
  views.frames = std::max(views.frames, frames);
}

namespace {

hsize_t length_of(hid_t file, const char* name) {
  H5Handle set = h5_check(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose, name);
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, name);
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  return dims[0];
}

}  // namespace

XdmfViews read_xdmf_views(hid_t file, std::size_t particles, std::size_t frames) {
  XdmfViews views;
  views.particles = particles;
  views.cell_values = length_of(file, "/xdmf/cells");
  views.cells = length_of(file, "/xdmf/cell_object");
  H5Handle group = h5_check(H5Gopen2(file, "xdmf/frames", H5P_DEFAULT), H5Gclose, "/xdmf/frames");
  std::size_t have = 0;
  while (H5Lexists(group, std::to_string(have).c_str(), H5P_DEFAULT) > 0) ++have;
  for (std::size_t f = frames; f < have; ++f) {
    h5_check(H5Ldelete(group, std::to_string(f).c_str(), H5P_DEFAULT), "deleting a frame view");
  }
  views.frames = std::min(have, frames);
  return views;
}

}  // namespace atssim::io
