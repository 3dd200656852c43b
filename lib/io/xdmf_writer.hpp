#pragma once
// The XDMF sidecar that lets ParaView (and meshio's TimeSeriesReader) open
// an atssim HDF5 file as a time series: a temporal collection with one
// uniform grid per frame, whose cells are every object's surface triangles
// and tetrahedra (/xdmf/cells, one Mixed topology) and whose geometry is the
// frame's view /xdmf/frames/<k> (io/xdmf_views.hpp). Cell attribute
// "object" numbers the objects in the order the Information "objects" lists
// them; node attribute "positions" repeats the geometry for readers that
// take per-frame data from attributes only (meshio).
#include <string>
#include <vector>

#include "io/xdmf_views.hpp"

namespace atssim::io {

// Writes atomically (temporary file + rename). `h5_name` is the HDF5 file
// name relative to the sidecar's folder. Frames without a view (all of them
// while the run writes; none once it has ended) get their geometry as an
// XDMF 3 hyperslab of /frames/positions, which ParaView reads and meshio
// does not, and no "positions" attribute.
void write_xdmf_file(const std::string& xdmf_path, const std::string& h5_name, const XdmfViews& views,
                     const std::vector<std::string>& object_names, const std::vector<double>& times);

// The sidecar while a run writes: written whole once, then one grid per
// flushed frame written in place over the closing tags (which follow it in
// the same write), so it lists every flushed frame at a cost that does not
// grow with the frame count. Throws atssim::Error (runtime) when a write fails.
class XdmfStream {
 public:
  XdmfStream() = default;
  XdmfStream(const std::string& xdmf_path, const std::string& h5_name, const XdmfViews& views,
             const std::vector<std::string>& object_names, const std::vector<double>& times);
  XdmfStream(const XdmfStream&) = delete;
  XdmfStream& operator=(const XdmfStream&) = delete;
  XdmfStream(XdmfStream&& other) noexcept;
  XdmfStream& operator=(XdmfStream&& other) noexcept;
  ~XdmfStream();

  void append(double time);
  void close();

 private:
  std::string path_, h5_;
  XdmfViews views_;
  int fd_ = -1;
  long long tail_at_ = 0;
  std::size_t frames_ = 0;
};

}  // namespace atssim::io
