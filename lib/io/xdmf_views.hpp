#pragma once
// What the XDMF sidecar points at, written into the HDF5 file beside the
// frames (/xdmf, docs/output-format.md): the cells of every object in one
// XDMF "Mixed" list over global vertex indices, the object of each cell, and
// per frame a virtual dataset that is that frame's [N, 3] slice of
// /frames/positions. The frame views let readers that take one whole dataset
// per XDMF item (meshio) read the frames; they hold no frame data.
#include <cstddef>
#include <span>

#include <hdf5.h>

#include "model/model.hpp"

namespace atssim::io {

struct XdmfViews {
  std::size_t particles = 0;
  std::size_t cells = 0;        // triangles + tetrahedra of all objects
  std::size_t cell_values = 0;  // length of /xdmf/cells (type code + vertices per cell)
  std::size_t frames = 0;       // frames that have a view /xdmf/frames/<k>
};

// XDMF cell type codes (XdmfTopologyType).
constexpr int kXdmfTriangle = 4;
constexpr int kXdmfTetrahedron = 6;

// Creates /xdmf with the cells and an empty /xdmf/frames.
XdmfViews write_xdmf_cells(hid_t file, std::span<const model::ObjectRange> objects, std::size_t particles);

// Adds the views of frames views.frames … frames − 1 (the writer does it when the run ends: one view costs ~0.3 ms, so
// views made up front would cost a long run seconds before its first frame).
void write_frame_views(hid_t file, XdmfViews& views, std::size_t frames);

// The views of a file written before (a resumed run), keeping those of its
// first `frames` frames and deleting the others.
XdmfViews read_xdmf_views(hid_t file, std::size_t particles, std::size_t frames);

}  // namespace atssim::io
