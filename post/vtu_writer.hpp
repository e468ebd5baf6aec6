// VTK XML UnstructuredGrid (.vtu) writer: one vertex cell per particle, binary (base64) arrays with
// 64-bit headers, readable by ParaView, VTK and meshio. Plus the .pvd time-series index.
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
  std::vector<std::int64_t> i64;  // ... or i64 holds the values
};

void write_vtu(const std::string& path, const std::vector<double>& points, const std::vector<VtuArray>& point_data);

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames);

}  // namespace rk
