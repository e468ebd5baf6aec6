// rkpost's flow lines (post/flow_lines.hpp): a line is the material line through the particles nearest
// to it, one per layer along it, so it is straight at t = 0 on a straight particle lattice.
#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "flow_lines.hpp"

namespace {

// Particles on the plane x = 0 in columns 5/3 apart across y and layers 2.5 apart along z: lines asked
// 2.5 apart (the spacing of the scene, finer particles than it, as the upsetting's O-grid at 2.5 mm)
TEST(FlowLines, OneColumnPerLineWhereTheParticlesAreFinerThanTheSpacing) {
  std::vector<double> X;
  for (int layer = 0; layer < 5; ++layer)
    for (int column = 0; column < 7; ++column) X.insert(X.end(), {0.0, column * 5.0 / 3, layer * 2.5});
  rk::Scene::Output::FlowLines spec;
  spec.point = {0, 0, 0}, spec.normal = {1, 0, 0}, spec.direction = {0, 0, 1}, spec.spacing = 2.5;
  const rk::FlowLineSet set = rk::select_flow_lines(spec, X, 2.5);
  std::map<std::int64_t, std::vector<double>> y;  // per line its particles' y
  for (std::size_t p = 0; p < set.particles.size(); ++p) y[set.line[p]].push_back(X[3 * std::size_t(set.particles[p]) + 1]);
  ASSERT_EQ(y.size(), 5u);  // y = 0, 2.5, 5, 7.5, 10: the lines at 2.5 and 7.5 lie midway between two columns
  for (const auto& [line, ys] : y) {
    EXPECT_EQ(ys.size(), 5u) << "line " << line << ": one particle per layer";
    for (double v : ys) EXPECT_DOUBLE_EQ(v, ys.front()) << "line " << line << " zigzags between columns";
  }
}

}  // namespace
