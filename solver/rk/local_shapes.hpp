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
  // their N to `N` (the gradients are not formed): a body's shape functions never reach into
  // another. The caller reports a singular moment matrix.
  RkResult append(const double x[3], int body, std::vector<std::int32_t>& cols, std::vector<double>& N) const;

  // Appends the particles of `body` whose supports cover x (the columns append would give, unsorted across calls).
  void covering(const double x[3], int body, std::vector<std::int32_t>& cols) const;

  // One search for a cell's `count` points at x (3 each): into `candidates` (replaced, ascending) the
  // particles of `body` whose supports may cover one of them; covering_among then gives each point's
  // columns, those append gives, from them.
  void near_group(const double* x, std::size_t count, int body, std::vector<std::int32_t>& candidates) const;
  void covering_among(const double x[3], const std::vector<std::int32_t>& candidates, std::vector<std::int32_t>& cols) const {
    grid_.covering_among(x, candidates, cols);
  }

  // N and grad N at x of the columns `cols` (covering's), into N[cols.size()] and dN[3 cols.size()].
  RkResult evaluate(const double x[3], std::span<const std::int32_t> cols, double* N, double* dN) const {
    return rk_shape(x, cols, particles_, kernel_, basis_, N, dN);
  }

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
