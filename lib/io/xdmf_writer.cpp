#include "io/xdmf_writer.hpp"

#include <filesystem>
#include <fstream>

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

}  // namespace

void write_xdmf_file(const std::string& xdmf_path, const std::string& h5_name, const XdmfViews& views,
                     const std::vector<std::string>& object_names, const std::vector<double>& times) {
  std::string names;
  for (std::size_t k = 0; k < object_names.size(); ++k)
    names += fmt::format("{}{}: {}", k ? "; " : "", k, object_names[k]);
  const std::string h5 = xml_escaped(h5_name);
  std::string x = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
  x += fmt::format("  <Information Name=\"objects\" Value=\"{}\"/>\n", xml_escaped(names));
  x += "  <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t f = 0; f < times.size(); ++f) x += frame_grid(h5, views, f, times.size(), times[f]);
  x += "  </Grid>\n </Domain>\n</Xdmf>\n";

  const std::string tmp = xdmf_path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << x;
    if (!out) throw runtime_error(fmt::format("cannot write '{}'", tmp));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, xdmf_path, ec);
  if (ec) throw runtime_error(fmt::format("cannot write '{}': {}", xdmf_path, ec.message()));
}

}  // namespace atssim::io
