// rkpost's fold finder (post/folds.hpp): two parts of the free surface that close in on each other
// are a fold; a surface squeezed along itself, its particles crowding but facing the same way, is not.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "folds.hpp"

namespace {

// A block of n x 2 x 2 unit hexahedra along x (spacing 1), particles numbered x-fastest.
struct Bar {
  rk::VtuCells cells;
  std::vector<double> X;
};

Bar bar(int n, double x0 = 0) {
  Bar b;
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= n; ++i) b.X.insert(b.X.end(), {x0 + i, double(j), double(k)});
  const auto id = [&](int i, int j, int k) { return std::int64_t((k * 3 + j) * (n + 1) + i); };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < n; ++i) {
        const std::int64_t c[8] = {id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
                                   id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        b.cells.connectivity.insert(b.cells.connectivity.end(), c, c + 8);
        b.cells.offsets.push_back(std::int64_t(b.cells.connectivity.size()));
        b.cells.types.push_back(rk::kVtkHexahedron);
      }
  return b;
}

TEST(Folds, TwoFacesClosingInAreAFold) {
  // two blocks of 2 x 2 x 2 cells, 3 spacings apart end to end; the second slides to 0.3 of a spacing
  Bar a = bar(2), b = bar(2, 5);
  Bar both = a;
  const std::int64_t shift = std::int64_t(a.X.size() / 3);
  for (std::int64_t v : b.cells.connectivity) both.cells.connectivity.push_back(v + shift);
  for (std::int64_t o : b.cells.offsets) both.cells.offsets.push_back(o + std::int64_t(a.cells.connectivity.size()));
  both.cells.types.insert(both.cells.types.end(), b.cells.types.begin(), b.cells.types.end());
  both.X.insert(both.X.end(), b.X.begin(), b.X.end());
  rk::FoldFinder finder(both.cells, both.X, 1.0, {});
  std::vector<rk::Fold> found;
  const std::vector<std::int64_t> start = finder.find(both.X, 0.0, found);  // 3 spacings apart: none
  EXPECT_EQ(std::count(start.begin(), start.end(), 1), 0);
  std::vector<double> x = both.X;
  for (std::size_t I = std::size_t(shift); I < x.size() / 3; ++I) x[3 * I] -= 2.7;  // its end face at x = 2.3
  const std::vector<std::int64_t> flags = finder.find(x, 1.0, found);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].time, 1.0);
  // the end faces' centres, whose normals are the faces' (at their edges and corners the sides' count
  // as much: not facing)
  EXPECT_NEAR(found[0].at[0], 2.15, 1e-12);  // between the faces at x = 2 and 2.3
  EXPECT_NEAR(found[0].at[1], 1.0, 1e-12);
  EXPECT_EQ(found[0].particles, 2u);
  EXPECT_EQ(std::count(flags.begin(), flags.end(), 1), 2);
}

TEST(Folds, ASurfaceSqueezedAlongItselfIsNone) {
  // a block 6 cells long squeezed to a fifth of its length: particles two spacings apart come within
  // 0.4 of a spacing of each other on the same faces, facing the same way
  Bar b = bar(6);
  rk::FoldFinder finder(b.cells, b.X, 1.0, {});
  std::vector<double> x = b.X;
  for (std::size_t I = 0; I < x.size() / 3; ++I) x[3 * I] *= 0.2;
  std::vector<rk::Fold> found;
  const std::vector<std::int64_t> flags = finder.find(x, 1.0, found);
  EXPECT_EQ(std::count(flags.begin(), flags.end(), 1), 0);
  EXPECT_TRUE(found.empty());
}

}  // namespace
