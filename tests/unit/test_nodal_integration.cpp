// Nodal integration (prep/nodal_integration.hpp, solver/model.cpp): the dual cells tile the mesh (their
// volumes sum to the cells' volume), each one is closed and its face quadrature integrates linear
// fields exactly (sum_q (x_q - X_L) nA_q^T = V_L I), so the smoothed gradients of the RK shape
// functions reproduce linear fields exactly; a node's row is bitwise the same on any partition.
// Meshes: structured hexahedra (the Taylor bar), distorted hexahedra (a STEP box through gmsh's
// subdivision) and tetrahedra.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <unistd.h>

#include "cad_mesh.hpp"
#include "discretize.hpp"
#include "model.hpp"
#include "nodal_integration.hpp"
#include "partition.hpp"
#include "scene.hpp"
#include "source_dir.hpp"

namespace {

using rk::test::kSource;

// Written when the test cases are listed, so by every test process that ctest starts: one file per process
// (a shared one was rewritten under a reader running beside it, which then read an empty box), removed at
// the process's end.
struct TetBoxFile {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("rk_nodal_tet_box_" + std::to_string(::getpid()) + ".geo");
  TetBoxFile() {
    std::ofstream(path) << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 10, 6, 4};\nMesh.MeshSizeMax = h;\n"
                           "Mesh.MeshSizeMin = h;\n";
  }
  ~TetBoxFile() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
};

std::string tet_box_geo() {
  static const TetBoxFile file;
  return file.path.string();
}

struct MeshCase {
  std::string name, cad;
  double spacing;  // m (CAD in mm)
};

void PrintTo(const MeshCase& c, std::ostream* os) { *os << c.name; }

rk::VolumeMesh mesh_of(const MeshCase& c) { return rk::mesh_cad({c.cad, 1e-3, c.spacing}); }

class NodalIntegration : public ::testing::TestWithParam<MeshCase> {};

TEST_P(NodalIntegration, DualCellsTileTheMeshAndIntegrateLinearFieldsExactly) {
  const rk::VolumeMesh mesh = mesh_of(GetParam());
  const rk::DualFaces f = rk::dual_faces(mesh);
  const std::vector<double> V = rk::dual_volumes(mesh, f);
  const rk::Discretization gauss = rk::discretize(mesh, 2);
  double total = 0, cells = 0;
  for (double v : V) total += v;
  for (double w : gauss.point_weight) cells += w;
  EXPECT_NEAR(total / cells, 1.0, 1e-12) << "the dual cells tile the mesh";

  std::vector<std::array<double, 12>> sums(mesh.node_count(), std::array<double, 12>{});  // S (9), sum nA (3)
  for (std::size_t q = 0; q < f.size(); ++q)
    for (const std::int32_t L : {f.plus[q], f.minus[q]}) {
      if (L < 0) continue;
      const double sign = L == f.plus[q] ? 1.0 : -1.0;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) sums[L][3 * i + j] += sign * (f.X[3 * q + i] - mesh.X[3 * L + i]) * f.nA[3 * q + j];
        sums[L][9 + i] += sign * f.nA[3 * q + i];
      }
    }
  double worst_S = 0, worst_closed = 0;
  for (std::size_t L = 0; L < mesh.node_count(); ++L) {
    ASSERT_GT(V[L], 0) << "node " << L;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) worst_S = std::max(worst_S, std::abs(sums[L][3 * i + j] / V[L] - (i == j)));
      worst_closed = std::max(worst_closed, std::abs(sums[L][9 + i]) / std::pow(V[L], 2.0 / 3));
    }
  }
  EXPECT_LT(worst_S, 1e-12) << "sum_q (x_q - X_L) nA_q^T = V_L I";
  EXPECT_LT(worst_closed, 1e-12) << "every dual cell is closed";
}

// The solver's smoothed gradients, from the subdomain files' data, on 1 and 3 ranks.
TEST_P(NodalIntegration, SmoothedGradientsReproduceLinearFieldsOnEveryPartition) {
  const rk::VolumeMesh mesh = mesh_of(GetParam());
  const auto scene = rk::load_scene(kSource + "/geometry/taylor_bar/scene.yaml",
                                    {{"discretization.integration", "nodal"},
                                     {"discretization.spacing", std::to_string(GetParam().spacing)}});
  rk::Discretization disc = rk::discretize(mesh, 2);
  rk::use_nodal_points(mesh, disc);
  ASSERT_EQ(disc.point_weight.size(), mesh.node_count());
  std::map<std::int64_t, std::vector<double>> rows_on_one_rank;  // node -> its dN row
  std::map<std::array<double, 3>, std::int64_t> node_at;  // the node a point sits on
  for (std::size_t I = 0; I < mesh.node_count(); ++I)
    node_at[{mesh.X[3 * I], mesh.X[3 * I + 1], mesh.X[3 * I + 2]}] = std::int64_t(I);
  for (const int ranks : {1, 3}) {
    const auto cell_rank = rk::partition_cells(mesh, disc, ranks, "metis-kway");
    const auto subs = rk::build_subdomains({mesh, disc, cell_rank, ranks, scene.discretization.dilation, "hash", {}});
    std::size_t points = 0, compared = 0;
    double worst = 0;
    for (const auto& sub : subs) {
      const rk::Model md = rk::build_model(sub, scene);
      points += md.m;
      for (std::size_t g = 0; g < md.m; ++g) {
        double grad[9] = {}, sum[3] = {};
        std::map<std::int64_t, std::vector<double>> row;
        for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) {
          const std::size_t I = std::size_t(md.nbr[k]);
          for (int i = 0; i < 3; ++i) {
            sum[i] += md.dN[3 * k + i];
            for (int j = 0; j < 3; ++j) grad[3 * i + j] += md.X[3 * I + i] * md.dN[3 * k + j];
          }
          row[md.global_id[I]] = {md.dN[3 * k], md.dN[3 * k + 1], md.dN[3 * k + 2]};
        }
        for (int i = 0; i < 9; ++i) worst = std::max(worst, std::abs(grad[i] - (i % 4 == 0)));
        for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(sum[i]) * GetParam().spacing);
        const std::int64_t node = node_at.at({md.point_X[3 * g], md.point_X[3 * g + 1], md.point_X[3 * g + 2]});
        std::vector<double> flat;
        for (const auto& [id, d] : row) flat.push_back(double(id)), flat.insert(flat.end(), d.begin(), d.end());
        if (ranks == 1) rows_on_one_rank[node] = flat;
        else compared += rows_on_one_rank.at(node) == flat;
      }
    }
    EXPECT_EQ(points, mesh.node_count()) << ranks << " ranks: one point per node";
    EXPECT_LT(worst, 1e-9) << ranks << " ranks: sum_I X_I (x) b_I = I and sum_I b_I = 0";
    if (ranks > 1) {
      EXPECT_EQ(compared, mesh.node_count()) << "every row bitwise equal to the 1-rank row";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, NodalIntegration,
                         ::testing::Values(MeshCase{"structured_hex", kSource + "/geometry/taylor_bar/taylor_bar.geo", 1.2e-3},
                                           MeshCase{"subdivided_hex", kSource + "/tests/pipeline/data/step_box/box.step", 8e-3},
                                           MeshCase{"tet", tet_box_geo(), 2e-3}),
                         [](const auto& info) { return info.param.name; });

}  // namespace
