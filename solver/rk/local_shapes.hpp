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
  // X, volume, spacing, body: the local particles (3, 1, 1, 1 per particle; Model::body); they must
  // outlive this object.
  LocalShapes(const std::vector<double>& X, const std::vector<double>& volume, const std::vector<double>& spacing,
              const std::vector<std::uint8_t>& body, const Scene& scene);

  // Appends the particles of `body` whose supports cover x (ascending local index) to `cols`, and
  // their N and grad N (3 per column) to `N` and `dN`: a body's shape functions never reach into
  // another. The caller reports a singular moment matrix.
  RkResult append(const double x[3], int body, std::vector<std::int32_t>& cols, std::vector<double>& N,
                  std::vector<double>& dN) const;

  // Appends the particles of `body` whose supports cover x (the columns append would give, unsorted across calls).
  void covering(const double x[3], int body, std::vector<std::int32_t>& cols) const;

 private:
  std::vector<double> radius_;
  const std::vector<std::uint8_t>& body_;
  bool bodies_ = false;  // more than one body: the searches filter by body
  NeighbourGrid grid_;
  RkParticles particles_;
  Kernel kernel_;
  Basis basis_;
  mutable std::vector<std::int32_t> found_;
};

}  // namespace rk
