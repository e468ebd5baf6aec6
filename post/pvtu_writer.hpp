// VTK XML parallel UnstructuredGrid (.pvtu): the index of a dataset written as pieces, one .vtu each
// (post/vtu_writer.hpp), that ParaView reads in parallel (each pvbatch or pvserver process reads its
// share of the pieces) or, on one process, appended into one grid. It declares every point and cell
// array with its type and component count, as every piece holds them, and names the pieces by paths
// relative to the .pvtu's folder. Readable by ParaView 5.11.
#pragma once
#include <string>
#include <vector>

#include "vtu_writer.hpp"

namespace rk {

// An array as the .pvtu declares it: what every piece holds under that name.
struct PvtuArray {
  std::string name, type;  // type: a VTK type name (Float64, Int64, UInt8)
  int components = 1;
  bool operator==(const PvtuArray&) const = default;
};
std::vector<PvtuArray> pvtu_arrays(const std::vector<VtuArray>& arrays);

// pieces: the pieces' .vtu files relative to the .pvtu's folder. Points are Float64 x y z. No ghost
// cells (GhostLevel 0): points a piece holds for its cells but does not own are marked in its
// vtkGhostType point array instead.
void write_pvtu(const std::string& path, const std::vector<PvtuArray>& point_data,
                const std::vector<PvtuArray>& cell_data, const std::vector<std::string>& pieces);

}  // namespace rk
