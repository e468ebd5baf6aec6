#include "jitter.hpp"

#include <random>

namespace rk {

void jitter_interior(VolumeMesh& mesh, const std::vector<double>& spacing, double fraction) {
  if (fraction <= 0) return;
  std::mt19937_64 bits(20061121);  // the engine's sequence is fixed by the standard; the map below too
  auto unit = [&] { return double(bits() >> 11) * 0x1.0p-52 - 1.0; };  // [-1, 1)
  for (std::size_t I = 0; I < mesh.node_count(); ++I) {
    const double a = unit(), b = unit(), c = unit();  // drawn for every node: the layout of one does not
    if (mesh.surface[I]) continue;                    // depend on which others are on the surface
    mesh.X[3 * I] += fraction * spacing[I] * a;
    mesh.X[3 * I + 1] += fraction * spacing[I] * b;
    mesh.X[3 * I + 2] += fraction * spacing[I] * c;
  }
}

}  // namespace rk
