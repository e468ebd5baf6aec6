// RK shape functions of this rank's local particles at any point (integration points, constrained
// particles): the support search and the evaluation with the scene's kernel, basis and dilation.
#pragma once
#include <cstdint>
#include <vector>

#include "neighbour_grid.hpp"
#include "rk_shape.hpp"
#include "scene.hpp"

namespace rk {

class LocalShapes {
 public:
  // X, volume, spacing: the local particles (3, 1, 1 per particle); they must outlive this object.
  LocalShapes(const std::vector<double>& X, const std::vector<double>& volume, const std::vector<double>& spacing,
              const Scene& scene);

  // Appends the particles whose supports cover x (ascending local index) to `cols`, and their N
  // and grad N (3 per column) to `N` and `dN`. The caller reports a singular moment matrix.
  RkResult append(const double x[3], std::vector<std::int32_t>& cols, std::vector<double>& N,
                  std::vector<double>& dN) const;

  // Appends the particles whose supports cover x (the columns append would give, unsorted across calls).
  void covering(const double x[3], std::vector<std::int32_t>& cols) const { grid_.covering(x, cols); }

 private:
  std::vector<double> radius_;
  NeighbourGrid grid_;
  RkParticles particles_;
  Kernel kernel_;
  Basis basis_;
  mutable std::vector<std::int32_t> found_;
};

}  // namespace rk
