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
