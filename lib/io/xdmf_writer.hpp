#pragma once
// The XDMF sidecar that lets ParaView open an atssim HDF5 file as a time
// series: per frame and object, a triangle mesh whose geometry is a
// hyperslab of /frames/positions.
#include <string>
#include <vector>

#include "model/model.hpp"

namespace atssim::io {

// Writes atomically (temporary file + rename). `h5_name` is the HDF5 file
// name relative to the sidecar's folder.
void write_xdmf_file(const std::string& xdmf_path, const std::string& h5_name,
                     const std::vector<model::ObjectRange>& objects, std::size_t particles,
                     const std::vector<double>& times);

}  // namespace atssim::io
