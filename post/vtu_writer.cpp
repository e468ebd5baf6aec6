#include "vtu_writer.hpp"

#include <cstring>
#include <fstream>

#include "error.hpp"

namespace rk {
namespace {

std::string base64(const unsigned char* data, std::size_t n) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const unsigned v = (unsigned(data[i]) << 16) | (i + 1 < n ? unsigned(data[i + 1]) << 8 : 0u) |
                       (i + 2 < n ? unsigned(data[i + 2]) : 0u);
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < n ? table[(v >> 6) & 63] : '=';
    out += i + 2 < n ? table[v & 63] : '=';
  }
  return out;
}

template <class T>
void data_array(std::ofstream& f, const char* type, const std::string& name, int components, const std::vector<T>& v) {
  std::vector<unsigned char> bytes(8 + v.size() * sizeof(T));
  const std::uint64_t size = v.size() * sizeof(T);
  std::memcpy(bytes.data(), &size, 8);
  if (!v.empty()) std::memcpy(bytes.data() + 8, v.data(), size);
  f << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\"" << components
    << "\" format=\"binary\">\n          " << base64(bytes.data(), bytes.size()) << "\n        </DataArray>\n";
}

}  // namespace

void write_vtu(const std::string& path, const std::vector<double>& points, const std::vector<VtuArray>& point_data,
               const std::vector<std::int32_t>& triangles) {
  const std::size_t n = points.size() / 3;
  const std::size_t cells = triangles.empty() ? n : triangles.size() / 3;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    if (!f) throw Error(path + ": cannot write the VTK file");
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\""
      << n << "\" NumberOfCells=\"" << cells << "\">\n      <PointData>\n";
    for (const auto& a : point_data) {
      if (!a.i64.empty() || a.f64.empty()) data_array(f, "Int64", a.name, a.components, a.i64);
      else data_array(f, "Float64", a.name, a.components, a.f64);
    }
    f << "      </PointData>\n      <Points>\n";
    data_array(f, "Float64", "Points", 3, points);
    f << "      </Points>\n      <Cells>\n";
    const int per = triangles.empty() ? 1 : 3;
    std::vector<std::int64_t> conn(per * cells), offsets(cells);
    std::vector<std::uint8_t> types(cells, triangles.empty() ? 1 : 5);  // VTK_VERTEX or VTK_TRIANGLE
    for (std::size_t i = 0; i < per * cells; ++i) conn[i] = triangles.empty() ? std::int64_t(i) : triangles[i];
    for (std::size_t c = 0; c < cells; ++c) offsets[c] = std::int64_t(per * (c + 1));
    data_array(f, "Int64", "connectivity", 1, conn);
    data_array(f, "Int64", "offsets", 1, offsets);
    data_array(f, "UInt8", "types", 1, types);
    f << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    if (!f.flush()) throw Error(path + ": write failed (disk full?)");
  }
  std::rename(tmp.c_str(), path.c_str());
}

void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries) {
  std::ofstream f(path);
  if (!f) throw Error(path + ": cannot write the ParaView collection");
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n";
  f.precision(12);
  for (const auto& e : entries)
    f << "    <DataSet timestep=\"" << e.time << "\" part=\"" << e.part << "\" file=\"" << e.file << "\"/>\n";
  f << "  </Collection>\n</VTKFile>\n";
}

}  // namespace rk
