// Multi-rate steps' classes (solver/subcycles.hpp) on a chain of 8 cells, one point each, whose row holds
// the particles at its two ends (particles 0 .. 8): cells 0 and 1 hold only the smallest step, the rest
// 16 times it, as a crushed foot beside the shank.
#include <gtest/gtest.h>

#include <vector>

#include "subcycles.hpp"

namespace {

rk::Model chain() {
  rk::Model md;
  md.cells = 8, md.m = 8, md.n = 9;
  for (std::int32_t c = 0; c <= 8; ++c) md.cell_points.push_back(c);
  md.nbr_offsets.push_back(0);
  for (std::int32_t g = 0; g < 8; ++g) {
    md.nbr.push_back(g), md.nbr.push_back(g + 1);
    md.nbr_offsets.push_back(md.nbr_offsets.back() + 2);
    (g < 4 ? md.boundary_points : md.interior_points).push_back(g);
  }
  return md;
}

const rk::Subcycles::SumOverRanks one_rank = [](std::vector<rk::Fixed>&) {};
const rk::Subcycles::LargestOverRanks alone = [](int k) { return k; };

std::vector<int> particle_classes(const rk::Subcycles& s, const rk::Model& md) {
  std::vector<int> k;
  for (std::size_t I = 0; I < md.n; ++I) k.push_back(s.particle_class(I));
  return k;
}

std::vector<std::int32_t> list(std::span<const std::int32_t> s) { return {s.begin(), s.end()}; }

TEST(Subcycles, ClassesFromTheCellsStepsAndTheirRows) {
  const rk::Model md = chain();
  const double dt = 1e-9;
  const std::vector<double> dt_cell = {dt, 1.5 * dt, 16 * dt, 16 * dt, 17 * dt, 40 * dt, 16 * dt, 16 * dt};
  rk::Subcycles s(md, 16);
  EXPECT_EQ(s.max_levels(), 4);
  EXPECT_TRUE(s.starts(0)) << "the first step of a run starts a cycle";
  s.plan(md, dt_cell, dt, 4, 0, one_rank, alone);
  // a particle: the least class its cells allow (cells 0, 1: 0; the others: 4)
  EXPECT_EQ(particle_classes(s, md), (std::vector<int>{0, 0, 0, 4, 4, 4, 4, 4, 4}));
  // a cell: the least class of its particles (cell 2 holds particle 2, of class 0)
  EXPECT_EQ(list(s.cells(0)), (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(list(s.cells(3)), (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(list(s.cells(4)).size(), 8u);
  EXPECT_EQ(list(s.boundary_points(0)), (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_TRUE(s.interior_points(3).empty());
  EXPECT_EQ(s.interior_points(4).size(), 4u);
  // the classes due at each offset of the cycle of 16: those k with 2^k dividing it (all at its start)
  const int due[16] = {4, 0, 1, 0, 2, 0, 1, 0, 3, 0, 1, 0, 2, 0, 1, 0};
  for (int o = 0; o < 16; ++o) {
    EXPECT_EQ(s.level(o), due[o]) << "offset " << o;
    EXPECT_FALSE(s.starts(o)) << "offset " << o << ": inside the cycle planned at 0";
  }
  EXPECT_TRUE(s.starts(16)) << "the next cycle";
}

TEST(Subcycles, AShorterCycleCapsTheClasses) {
  const rk::Model md = chain();
  const double dt = 1e-9;
  const std::vector<double> dt_cell = {dt, dt, 5 * dt, 5 * dt, 5 * dt, 5 * dt, 40 * dt, 40 * dt};
  rk::Subcycles s(md, 16);
  s.plan(md, dt_cell, dt, 2, 32, one_rank, alone);  // a cycle of 4 steps (an output time ahead)
  // 5 dt holds 4 dt (class 2); 40 dt would hold 16 dt, capped at the cycle's 2
  EXPECT_EQ(particle_classes(s, md), (std::vector<int>{0, 0, 0, 2, 2, 2, 2, 2, 2}));
  EXPECT_EQ(list(s.cells(2)).size(), 8u);
  EXPECT_EQ(s.level(32), 2);
  EXPECT_EQ(s.level(34), 1);
  EXPECT_TRUE(s.starts(36));
  EXPECT_FALSE(s.starts(35));
}

TEST(Subcycles, ACycleIsAsLongAsItsLargestClassNeeds) {
  const rk::Model md = chain();
  const double dt = 1e-9;
  rk::Subcycles s(md, 16);
  s.plan(md, std::vector<double>(8, 1.5 * dt), dt, 4, 0, one_rank, alone);  // every cell at the smallest step
  EXPECT_EQ(particle_classes(s, md), std::vector<int>(9, 0));
  EXPECT_TRUE(s.starts(1)) << "a cycle of one step: frames and rows are not held back";
  s.plan(md, std::vector<double>(8, 5 * dt), dt, 4, 1, one_rank, alone);  // at most 4 dt
  EXPECT_FALSE(s.starts(4));
  EXPECT_TRUE(s.starts(5));
  s.plan(md, std::vector<double>(8, 1.5 * dt), dt, 4, 5, one_rank, [](int) { return 3; });  // another rank's 3
  EXPECT_FALSE(s.starts(12));
  EXPECT_TRUE(s.starts(13));
}

TEST(Subcycles, AParticleThatMetAContactTakesTheSmallestStep) {
  const rk::Model md = chain();
  const double dt = 1e-9;
  const std::vector<double> dt_cell(8, 16 * dt);
  rk::Subcycles s(md, 16);
  s.plan(md, dt_cell, dt, 4, 0, one_rank, alone);
  EXPECT_EQ(particle_classes(s, md), std::vector<int>(9, 4));
  std::vector<double> contact(27, 0.0);
  contact[3 * 5 + 2] = -1.0;  // particle 5, once in the cycle
  s.touch(contact);
  s.touch(std::vector<double>(27, 0.0));
  s.plan(md, dt_cell, dt, 4, 16, one_rank, alone);
  // particle 5 at class 0, and the cells holding it (4 and 5); the others keep theirs
  EXPECT_EQ(particle_classes(s, md), (std::vector<int>{4, 4, 4, 4, 4, 0, 4, 4, 4}));
  EXPECT_EQ(list(s.cells(0)), (std::vector<std::int32_t>{4, 5}));
  s.plan(md, dt_cell, dt, 4, 32, one_rank, alone);
  EXPECT_EQ(particle_classes(s, md), std::vector<int>(9, 4)) << "no contact in the last cycle";
}

TEST(Subcycles, TheOtherRanksCountsDecide) {
  // the counts summed over the ranks: another rank's cell of class 0 holds particle 8
  const rk::Model md = chain();
  const double dt = 1e-9;
  rk::Subcycles s(md, 16);
  s.plan(md, std::vector<double>(8, 16 * dt), dt, 4, 0, [](std::vector<rk::Fixed>& counts) { ++counts[4 * 8 + 0]; },
         alone);
  EXPECT_EQ(s.particle_class(8), 0);
  EXPECT_EQ(s.particle_class(7), 4);
  EXPECT_EQ(list(s.cells(0)), (std::vector<std::int32_t>{7}));
}

}  // namespace
