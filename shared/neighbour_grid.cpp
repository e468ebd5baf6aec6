#include "neighbour_grid.hpp"

#include <algorithm>
#include <cmath>

namespace rk {

NeighbourGrid::NeighbourGrid(const double* X, const double* radius, std::size_t n) : X_(X), radius_(radius) {
  double hi[3];
  for (int d = 0; d < 3; ++d) lo_[d] = hi[d] = n ? X[d] : 0.0;
  double rmax = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      lo_[d] = std::min(lo_[d], X[3 * i + d]);
      hi[d] = std::max(hi[d], X[3 * i + d]);
    }
    rmax = std::max(rmax, radius[i]);
  }
  h_ = rmax > 0 ? rmax : 1.0;
  for (int d = 0; d < 3; ++d) dims_[d] = std::max<std::int64_t>(1, std::int64_t((hi[d] - lo_[d]) / h_) + 1);
  std::vector<std::int64_t> bin(n);
  start_.assign(dims_[0] * dims_[1] * dims_[2] + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double* x = X + 3 * i;
    bin[i] = (bin_of(x, 2) * dims_[1] + bin_of(x, 1)) * dims_[0] + bin_of(x, 0);
    ++start_[bin[i] + 1];
  }
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  items_.resize(n);
  std::vector<std::int32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) items_[fill[bin[i]]++] = std::int32_t(i);
}

std::int64_t NeighbourGrid::bin_of(const double x[3], int d) const {
  return std::clamp<std::int64_t>(std::int64_t(std::floor((x[d] - lo_[d]) / h_)), 0, dims_[d] - 1);
}

void NeighbourGrid::covering(const double x[3], std::vector<std::int32_t>& out) const {
  const std::size_t first = out.size();
  std::int64_t b[3];
  for (int d = 0; d < 3; ++d) b[d] = std::int64_t(std::floor((x[d] - lo_[d]) / h_));
  for (std::int64_t k = std::max<std::int64_t>(b[2] - 1, 0); k <= std::min(b[2] + 1, dims_[2] - 1); ++k)
    for (std::int64_t j = std::max<std::int64_t>(b[1] - 1, 0); j <= std::min(b[1] + 1, dims_[1] - 1); ++j)
      for (std::int64_t i = std::max<std::int64_t>(b[0] - 1, 0); i <= std::min(b[0] + 1, dims_[0] - 1); ++i) {
        const std::int64_t bin = (k * dims_[1] + j) * dims_[0] + i;
        for (std::int32_t s = start_[bin]; s < start_[bin + 1]; ++s) {
          const std::int32_t I = items_[s];
          const double* p = X_ + 3 * I;
          const double r2 = (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) + (x[2] - p[2]) * (x[2] - p[2]);
          if (r2 < radius_[I] * radius_[I]) out.push_back(I);
        }
      }
  std::sort(out.begin() + first, out.end());
}

}  // namespace rk
