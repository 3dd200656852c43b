#pragma once
// What the XDMF sidecar points at, written into the HDF5 file beside the
// frames (/xdmf, docs/output-format.md): the cells of every object in one
// XDMF "Mixed" list over global vertex indices, the object of each cell, and
// per frame a virtual dataset that is that frame's [N, 3] slice of
// /frames/positions. The views let readers that take a whole dataset per
// item (meshio) and ParaView read the same file; they cost no frame data.
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

// Creates /xdmf in `file` (before SWMR writing starts: SWMR cannot create
// objects) with views for frames 0 … frames − 1.
XdmfViews write_xdmf_views(hid_t file, std::span<const model::ObjectRange> objects, std::size_t particles,
                           std::size_t frames);

}  // namespace atssim::io
