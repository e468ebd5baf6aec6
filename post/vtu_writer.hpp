// VTK XML UnstructuredGrid (.vtu) writer: raw appended binary arrays, zlib-compressed in 32 KiB blocks
// (vtkZLibDataCompressor, 64-bit headers), readable by ParaView 5.11, VTK and meshio. Plus the .pvd
// time-series index. Written directly rather than through VTK's writers: no VTK to build against
// (libvtk9-dev conflicts with python3-paraview on Debian 12) for a format this small.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rk {

struct VtuArray {
  std::string name;
  int components = 1;
  std::vector<double> f64;        // either f64 ...
  std::vector<std::int64_t> i64;  // ... or i64 ...
  std::vector<std::uint8_t> u8;   // ... or u8 holds the values
  VtuArray(std::string name, int components, std::vector<double> f64 = {}, std::vector<std::int64_t> i64 = {},
           std::vector<std::uint8_t> u8 = {})
      : name(std::move(name)), components(components), f64(std::move(f64)), i64(std::move(i64)), u8(std::move(u8)) {}
};
// The VTK type an array is written as: UInt8 where u8 holds its values, Float64 where f64 does, else
// Int64 (an array without values too).
const char* vtk_type(const VtuArray& a);

struct VtuCells {  // point indices of each cell, the end of each cell in them, the VTK cell types
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  void add(const std::int64_t* points, int count, std::uint8_t type);
  static VtuCells triangles(const std::vector<std::int32_t>& corners);  // VTK_TRIANGLE, 3 corners each
};
inline constexpr std::uint8_t kVtkTetra = 10, kVtkHexahedron = 12;

void write_vtu(const std::string& path, const std::vector<double>& points, const std::vector<VtuArray>& point_data,
               const VtuCells& cells, const std::vector<VtuArray>& cell_data = {}, bool compress = true);

struct PvdEntry {
  double time;
  int part;  // 0: the workpiece, 1..: the dies
  std::string file;
  std::string name;  // the block's name in ParaView ("part", or the die's name)
};
void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries);

}  // namespace rk
