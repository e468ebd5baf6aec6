#include "time_step.hpp"

#include <cmath>
#include <limits>

namespace rk {
namespace {
constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                  {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
constexpr int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
}  // namespace

StableStep stable_time_step(const Model& md, const State& st, double cfl) {
  double dt = std::numeric_limits<double>::infinity();
  std::size_t which = 0;
  for (std::size_t c = 0; c < md.cells; ++c) {
    const std::int32_t* nodes = &md.cell_nodes[md.cell_node_offsets[c]];
    const bool hex = md.cell_node_offsets[c + 1] - md.cell_node_offsets[c] == 8;
    const int count = hex ? 12 : 6;
    double l2 = std::numeric_limits<double>::infinity();
    for (int e = 0; e < count; ++e) {
      const int a = nodes[hex ? kHexEdges[e][0] : kTetEdges[e][0]], b = nodes[hex ? kHexEdges[e][1] : kTetEdges[e][1]];
      double d2 = 0;
      for (int i = 0; i < 3; ++i) {
        const double d = md.X[3 * a + i] + st.u[3 * a + i] - md.X[3 * b + i] - st.u[3 * b + i];
        d2 += d * d;
      }
      l2 = std::min(l2, d2);
    }
    const double c2 = md.wave_modulus * std::max(st.cell_J[c], 1e-12) / md.density;
    const double dtc = std::sqrt(l2 / c2);
    if (dtc < dt) dt = dtc, which = c;
  }
  return {cfl * dt, which};
}

}  // namespace rk
