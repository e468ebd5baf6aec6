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
        for (std::int32_t s = start_[bin]; s < start_[bin + 1]; ++s)
          if (covers(x, items_[s])) out.push_back(items_[s]);
      }
  std::sort(out.begin() + first, out.end());
}

void NeighbourGrid::near_group(const double* x, std::size_t count, std::vector<std::int32_t>& out) const {
  if (count == 0) return;
  double c[3] = {0, 0, 0}, reach2 = 0;  // the group's ball: its centroid and the farthest point from it
  for (std::size_t k = 0; k < count; ++k)
    for (int d = 0; d < 3; ++d) c[d] += x[3 * k + d] / double(count);
  for (std::size_t k = 0; k < count; ++k) {
    double r2 = 0;
    for (int d = 0; d < 3; ++d) r2 += (x[3 * k + d] - c[d]) * (x[3 * k + d] - c[d]);
    reach2 = std::max(reach2, r2);
  }
  // a particle covering a point of the ball lies within a_I + reach of c; widened by a millionth
  // (round-off), a few extra candidates cost nothing: covering_among decides
  const double reach = std::sqrt(reach2), slack = 1 + 1e-6, R = (h_ + reach) * slack;
  std::int64_t from[3], to[3];
  for (int d = 0; d < 3; ++d) {
    from[d] = std::max<std::int64_t>(std::int64_t(std::floor((c[d] - R - lo_[d]) / h_)), 0);
    to[d] = std::min<std::int64_t>(std::int64_t(std::floor((c[d] + R - lo_[d]) / h_)), dims_[d] - 1);
  }
  const std::size_t first = out.size();
  for (std::int64_t k = from[2]; k <= to[2]; ++k)
    for (std::int64_t j = from[1]; j <= to[1]; ++j)
      for (std::int64_t i = from[0]; i <= to[0]; ++i) {
        const std::int64_t bin = (k * dims_[1] + j) * dims_[0] + i;
        for (std::int32_t s = start_[bin]; s < start_[bin + 1]; ++s) {
          const std::int32_t I = items_[s];
          const double* p = X_ + 3 * I;
          const double r2 = (c[0] - p[0]) * (c[0] - p[0]) + (c[1] - p[1]) * (c[1] - p[1]) + (c[2] - p[2]) * (c[2] - p[2]);
          const double RI = (radius_[I] + reach) * slack;
          if (r2 < RI * RI) out.push_back(I);
        }
      }
  std::sort(out.begin() + std::ptrdiff_t(first), out.end());
}

void NeighbourGrid::covering_among(const double x[3], const std::vector<std::int32_t>& candidates,
                                   std::vector<std::int32_t>& out) const {
  for (auto I : candidates)
    if (covers(x, I)) out.push_back(I);
}

}  // namespace rk
