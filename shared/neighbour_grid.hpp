// Bucket grid for support searches: which particles' supports (radius a_I) cover a point.
// Bin size = the largest support radius, so a query visits the 27 bins around the point.
#pragma once
#include <cstdint>
#include <vector>

namespace rk {

class NeighbourGrid {
 public:
  NeighbourGrid(const double* X, const double* radius, std::size_t n);

  // Appends to `out` the particles I with |x - X_I| < a_I, in ascending index order.
  void covering(const double x[3], std::vector<std::int32_t>& out) const;

  // One search for a group of points (an integration cell's): appends to `out`, ascending, the
  // particles whose supports may cover any of the `count` points at x (3 each), those within their
  // radius of the group's ball; covering_among then picks each point's columns from them.
  void near_group(const double* x, std::size_t count, std::vector<std::int32_t>& out) const;

  // Appends to `out` the particles of `candidates` (ascending) whose supports cover x, in their order:
  // covering(x)'s answer where the candidates hold it (near_group's for a group holding x).
  void covering_among(const double x[3], const std::vector<std::int32_t>& candidates, std::vector<std::int32_t>& out) const;

  // |x - X_I| < a_I: whether particle I's support covers x (the one test of the searches)
  bool covers(const double x[3], std::int32_t I) const {
    const double* p = X_ + 3 * I;
    const double r2 = (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) + (x[2] - p[2]) * (x[2] - p[2]);
    return r2 < radius_[I] * radius_[I];
  }

  std::size_t size() const { return items_.size(); }  // the particles it holds

 private:
  std::int64_t bin_of(const double x[3], int d) const;
  const double* X_;
  const double* radius_;
  double lo_[3]{}, h_ = 1;
  std::int64_t dims_[3]{1, 1, 1};
  std::vector<std::int32_t> start_, items_;  // CSR: particles per bin
};

}  // namespace rk
