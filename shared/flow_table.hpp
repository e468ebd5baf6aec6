// A flow stress table sigma_y(strain, strain rate, temperature) from a CSV file, as the hot-forging
// databases export it: a header `strain,strain_rate,temperature,stress` (-, 1/s, K, Pa), then one row
// per point of a full grid, sorted by temperature, then strain rate, then strain, each ascending
// (every combination once: no gaps). Read and checked in one place; a bad file is an rk::Error naming
// the file and the row. Interpolation is trilinear in (strain, ln rate, temperature); outside the
// table each coordinate is held at the table's edge (the stress is constant beyond it).
#pragma once
#include <string>
#include <vector>

namespace rk {

struct FlowTable {
  std::string file;
  std::vector<double> strain, rate, temperature;  // the axes, strictly ascending (rate > 0)
  std::vector<double> stress;  // [temperature][rate][strain], Pa

  // The flow stress and its slopes d/d strain and d/d rate at (strain, rate, T) (0 beyond the edges).
  void at(double ep, double r, double T, double& y, double& dy_dep, double& dy_drate) const;
};

FlowTable read_flow_table(const std::string& path);

}  // namespace rk
