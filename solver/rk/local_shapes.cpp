#include "rk/local_shapes.hpp"

#include <algorithm>

namespace rk {
namespace {

std::vector<double> radii(const std::vector<double>& spacing, double dilation) {
  std::vector<double> r(spacing.size());
  for (std::size_t I = 0; I < r.size(); ++I) r[I] = dilation * spacing[I];
  return r;
}

}  // namespace

LocalShapes::LocalShapes(const std::vector<double>& X, const std::vector<double>& volume,
                         const std::vector<double>& spacing, const std::vector<std::uint8_t>& body, const Scene& scene)
    : radius_(radii(spacing, scene.discretization.dilation)),
      body_(body),
      bodies_(std::any_of(body.begin(), body.end(), [](std::uint8_t b) { return b != 0; })),
      grid_(X.data(), radius_.data(), spacing.size()),
      particles_{X.data(), volume.data(), radius_.data()},
      kernel_(parse_kernel(scene.discretization.kernel)),
      basis_(parse_basis(scene.discretization.basis)) {}

void LocalShapes::covering(const double x[3], int body, std::vector<std::int32_t>& cols) const {
  const std::size_t k0 = cols.size();
  grid_.covering(x, cols);
  if (bodies_)
    cols.erase(std::remove_if(cols.begin() + std::ptrdiff_t(k0), cols.end(), [&](std::int32_t J) { return body_[std::size_t(J)] != body; }),
               cols.end());
}

void LocalShapes::near_group(const double* x, std::size_t count, int body, std::vector<std::int32_t>& candidates) const {
  candidates.clear();
  grid_.near_group(x, count, candidates);
  if (bodies_) std::erase_if(candidates, [&](std::int32_t J) { return body_[std::size_t(J)] != body; });
}

RkResult LocalShapes::append(const double x[3], int body, std::vector<std::int32_t>& cols, std::vector<double>& N) const {
  found_.clear();
  covering(x, body, found_);
  const std::size_t k0 = cols.size();
  cols.insert(cols.end(), found_.begin(), found_.end());
  N.resize(cols.size());
  return rk_shape(x, found_, particles_, kernel_, basis_, &N[k0], nullptr);
}

}  // namespace rk
