#include "pvtu_writer.hpp"

#include <sstream>

#include "text_file.hpp"

namespace rk {

std::vector<PvtuArray> pvtu_arrays(const std::vector<VtuArray>& arrays) {
  std::vector<PvtuArray> out;
  for (const auto& a : arrays) out.push_back({a.name, vtk_type(a), a.components});
  return out;
}

void write_pvtu(const std::string& path, const std::vector<PvtuArray>& point_data,
                const std::vector<PvtuArray>& cell_data, const std::vector<std::string>& pieces) {
  std::ostringstream f;
  const auto declare = [&](const std::vector<PvtuArray>& list) {
    for (const auto& a : list)
      f << "      <PDataArray type=\"" << a.type << "\" Name=\"" << a.name << "\" NumberOfComponents=\"" << a.components
        << "\"/>\n";
  };
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n";
  declare(point_data);
  f << "    </PPointData>\n    <PCellData>\n";
  declare(cell_data);
  f << "    </PCellData>\n    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
       "    </PPoints>\n";
  for (const auto& piece : pieces) f << "    <Piece Source=\"" << piece << "\"/>\n";
  f << "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_text_file(path, f.str());
}

}  // namespace rk
