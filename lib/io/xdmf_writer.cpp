#include "io/xdmf_writer.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::io {

void write_xdmf_file(const std::string& xdmf_path, const std::string& h5_name,
                     const std::vector<model::ObjectRange>& objects, std::size_t particles,
                     const std::vector<double>& times) {
  std::string x;
  x += "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
  x += "  <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t f = 0; f < times.size(); ++f) {
    x += fmt::format("   <Grid Name=\"frame{}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n", f);
    x += fmt::format("    <Time Value=\"{:.9g}\"/>\n", times[f]);
    for (const auto& obj : objects) {
      x += fmt::format("    <Grid Name=\"{}\" GridType=\"Uniform\">\n", obj.name);
      x += fmt::format(
          "     <Topology TopologyType=\"Triangle\" NumberOfElements=\"{}\">\n"
          "      <DataItem Dimensions=\"{} 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">{}:/mesh/{}/triangles"
          "</DataItem>\n     </Topology>\n",
          obj.triangles.size(), obj.triangles.size(), h5_name, obj.name);
      x += fmt::format(
          "     <Geometry GeometryType=\"XYZ\">\n"
          "      <DataItem ItemType=\"HyperSlab\" Dimensions=\"{} 3\" Type=\"HyperSlab\">\n"
          "       <DataItem Dimensions=\"3 3\" Format=\"XML\">{} {} 0 1 1 1 1 {} 3</DataItem>\n"
          "       <DataItem Dimensions=\"{} {} 3\" NumberType=\"Float\" Precision=\"4\" Format=\"HDF\">"
          "{}:/frames/positions</DataItem>\n"
          "      </DataItem>\n     </Geometry>\n    </Grid>\n",
          obj.vertex_count, f, obj.vertex_offset, obj.vertex_count, times.size(), particles, h5_name);
    }
    x += "   </Grid>\n";
  }
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
