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

// One vertex cell per point, or the given triangles (3 point indices each) when not empty.
void write_vtu(const std::string& path, const std::vector<double>& points, const std::vector<VtuArray>& point_data,
               const std::vector<std::int32_t>& triangles = {});

struct PvdEntry {
  double time;
  int part;  // 0: the workpiece, 1..: the dies
  std::string file;
};
void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries);

}  // namespace rk
