#include "io/xdmf_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::io {

namespace {

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string frame_grid(const std::string& h5, const XdmfViews& v, std::size_t frame, std::size_t frames, double time) {
  std::string x =
      fmt::format("   <Grid Name=\"frame{}\" GridType=\"Uniform\">\n    <Time Value=\"{:.9g}\"/>\n", frame, time);
  x += fmt::format(
      "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"{}\">\n"
      "     <DataItem Dimensions=\"{}\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">{}:/xdmf/cells</DataItem>\n"
      "    </Topology>\n",
      v.cells, v.cell_values, h5);
  const bool has_view = frame < v.frames;
  const std::string positions = has_view ? fmt::format("{}:/xdmf/frames/{}", h5, frame)
                                         : fmt::format("{}:/frames/positions|{} 0 0:1 1 1:1 {} 3:{} {} 3", h5, frame,
                                                       v.particles, frames, v.particles);
  const std::string item = fmt::format(
      "     <DataItem Dimensions=\"{} 3\" NumberType=\"Float\" Precision=\"4\" Format=\"HDF\">{}</DataItem>\n",
      v.particles, positions);
  x += "    <Geometry GeometryType=\"XYZ\">\n" + item + "    </Geometry>\n";
  x += fmt::format(
      "    <Attribute Name=\"object\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
      "     <DataItem Dimensions=\"{}\" NumberType=\"Int\" Precision=\"4\" "
      "Format=\"HDF\">{}:/xdmf/cell_object</DataItem>\n"
      "    </Attribute>\n",
      v.cells, h5);
  if (has_view)
    x += "    <Attribute Name=\"positions\" AttributeType=\"Vector\" Center=\"Node\">\n" + item + "    </Attribute>\n";
  x += "   </Grid>\n";
  return x;
}

constexpr const char* kTail = "  </Grid>\n </Domain>\n</Xdmf>\n";

std::string xdmf_head(const std::vector<std::string>& object_names) {
  std::string names;
  for (std::size_t k = 0; k < object_names.size(); ++k)
    names += fmt::format("{}{}: {}", k ? "; " : "", k, object_names[k]);
  std::string x = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
  x += fmt::format("  <Information Name=\"objects\" Value=\"{}\"/>\n", xml_escaped(names));
  x += "  <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  return x;
}

}  // namespace

void write_xdmf_file(const std::string& xdmf_path, const std::string& h5_name, const XdmfViews& views,
                     const std::vector<std::string>& object_names, const std::vector<double>& times) {
  const std::string h5 = xml_escaped(h5_name);
  std::string x = xdmf_head(object_names);
  for (std::size_t f = 0; f < times.size(); ++f) x += frame_grid(h5, views, f, times.size(), times[f]);
  x += kTail;

  const std::string tmp = xdmf_path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << x;
    out.flush();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw runtime_error(fmt::format("cannot write '{}': {}", tmp, std::strerror(errno)));
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, xdmf_path, ec);
  if (ec) throw runtime_error(fmt::format("cannot write '{}': {}", xdmf_path, ec.message()));
}

XdmfStream::XdmfStream(const std::string& xdmf_path, const std::string& h5_name, const XdmfViews& views,
                       const std::vector<std::string>& object_names, const std::vector<double>& times)
    : path_(xdmf_path), h5_(xml_escaped(h5_name)), views_(views), frames_(times.size()) {
  views_.frames = 0;  // no views while the run writes: every frame is a hyperslab
  write_xdmf_file(xdmf_path, h5_name, views_, object_names, times);
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) throw runtime_error(fmt::format("cannot write '{}': {}", path_, std::strerror(errno)));
  const off_t end = ::lseek(fd_, 0, SEEK_END);
  tail_at_ = static_cast<long long>(end) - static_cast<long long>(std::strlen(kTail));
}

XdmfStream::XdmfStream(XdmfStream&& other) noexcept { *this = std::move(other); }
XdmfStream& XdmfStream::operator=(XdmfStream&& other) noexcept {
  if (this != &other) {
    close();
    path_ = std::move(other.path_);
    h5_ = std::move(other.h5_);
    views_ = other.views_;
    fd_ = std::exchange(other.fd_, -1);
    tail_at_ = other.tail_at_;
    frames_ = other.frames_;
  }
  return *this;
}
XdmfStream::~XdmfStream() { close(); }

void XdmfStream::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void XdmfStream::append(double time) {
  if (fd_ < 0) return;
  // Each grid states the positions' shape when it was listed (frame + 1
  // rows); readers take the one row it selects.
  const std::string grid = frame_grid(h5_, views_, frames_, frames_ + 1, time) + kTail;
  const ssize_t n = ::pwrite(fd_, grid.data(), grid.size(), static_cast<off_t>(tail_at_));
  if (n != static_cast<ssize_t>(grid.size())) {
    const int err = n < 0 ? errno : ENOSPC;
    throw runtime_error(fmt::format("cannot write '{}': {}", path_, std::strerror(err)));
  }
  tail_at_ += static_cast<long long>(grid.size() - std::strlen(kTail));
  ++frames_;
}

}  // namespace atssim::io
