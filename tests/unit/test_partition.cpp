// Partition invariants: every cell on exactly one rank, overlap maps symmetric between the
// two ranks of each pair and in ascending global id, every support particle present on the rank whose
// points need it, exactly one owner per particle and the owner holds it.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "cad_mesh.hpp"
#include "discretize.hpp"
#include "neighbour_grid.hpp"
#include "partition.hpp"
#include "source_dir.hpp"

namespace {

class Partition : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

TEST_P(Partition, Invariants) {
  const auto [ranks, method] = GetParam();
  const double dilation = 2.0;
  const rk::VolumeMesh mesh =
      rk::mesh_cad({rk::test::kSource + "/geometry/taylor_bar/taylor_bar.geo", 1e-3, 1.2e-3});
  const rk::Discretization disc = rk::discretize(mesh, 2);
  const auto cell_rank = rk::partition_cells(mesh, disc, ranks, method);
  const auto subs = rk::build_subdomains({mesh, disc, cell_rank, ranks, dilation, "hash", {}});
  ASSERT_EQ(int(subs.size()), ranks);

  std::vector<int> cell_count(mesh.cell_count(), 0);
  std::vector<int> owners(mesh.node_count(), 0);
  std::vector<double> radius(mesh.node_count());
  for (std::size_t i = 0; i < radius.size(); ++i) radius[i] = dilation * disc.spacing[i];
  rk::NeighbourGrid grid(mesh.X.data(), radius.data(), mesh.node_count());
  std::size_t points = 0;
  for (const auto& s : subs) {
    for (auto c : s.cell_global_id) ++cell_count[c];
    points += s.point_count();
    std::set<std::int64_t> local(s.global_id.begin(), s.global_id.end());
    for (std::size_t I = 0; I < s.particle_count(); ++I)
      if (s.owner[I] == s.rank) ++owners[s.global_id[I]];
    std::vector<std::int32_t> found;
    for (std::size_t g = 0; g < s.point_count(); ++g) {
      found.clear();
      grid.covering(&s.point_X[3 * g], found);
      for (auto I : found) ASSERT_TRUE(local.count(I)) << "rank " << s.rank << " lacks support particle " << I;
    }
    for (std::size_t k = 0; k < s.neighbour_ranks.size(); ++k) {
      const auto& other = subs[s.neighbour_ranks[k]];
      auto back = std::find(other.neighbour_ranks.begin(), other.neighbour_ranks.end(), s.rank);
      ASSERT_NE(back, other.neighbour_ranks.end()) << "overlap map " << s.rank << "->" << other.rank << " has no reverse";
      const auto& theirs = other.overlap[back - other.neighbour_ranks.begin()];
      ASSERT_EQ(theirs.size(), s.overlap[k].size());
      for (std::size_t j = 0; j < theirs.size(); ++j) {
        EXPECT_EQ(s.global_id[s.overlap[k][j]], other.global_id[theirs[j]]) << "same particle in both maps";
        if (j > 0) {
          EXPECT_GT(s.global_id[s.overlap[k][j]], s.global_id[s.overlap[k][j - 1]]) << "ascending global id";
        }
      }
    }
  }
  EXPECT_EQ(points, disc.point_weight.size());
  for (int c : cell_count) ASSERT_EQ(c, 1) << "every cell on exactly one rank";
  for (int o : owners) ASSERT_EQ(o, 1) << "every particle has exactly one owner";
  if (ranks > 1) {
    const auto report = rk::partition_report(subs, mesh.node_count());
    EXPECT_LT(report["imbalance"].get<double>(), 1.1);
    EXPECT_GT(report["overlap_fraction"].get<double>(), 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Ranks, Partition,
                         ::testing::Values(std::make_tuple(1, std::string("metis-kway")),
                                           std::make_tuple(3, std::string("metis-kway")),
                                           std::make_tuple(4, std::string("metis-recursive")),
                                           std::make_tuple(7, std::string("metis-kway"))),
                         [](const auto& info) {
                           std::string m = std::get<1>(info.param);
                           m.erase(std::remove(m.begin(), m.end(), '-'), m.end());
                           return std::to_string(std::get<0>(info.param)) + "ranks_" + m;
                         });

}  // namespace
