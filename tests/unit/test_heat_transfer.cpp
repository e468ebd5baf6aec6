// Heat exchange through the surface (solver/thermal/heat_transfer_laws.hpp) as pure laws, and the
// part's boundary faces that carry it (prep/cad_mesh.hpp): closed forms, no particles, no MPI.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cad_mesh.hpp"
#include "thermal/heat_transfer_laws.hpp"

namespace {

TEST(HeatTransferLaws, ConvectionAndContactFluxesFollowNewtonsLaw) {
  EXPECT_DOUBLE_EQ(rk::convection_flux(20, 293.15, 1423.15), 20 * (293.15 - 1423.15));  // into the part: < 0
  EXPECT_DOUBLE_EQ(rk::convection_flux(20, 600, 300), 6000);
  EXPECT_DOUBLE_EQ(rk::contact_flux(1e4, 523.15, 1423.15), -9e6);
  EXPECT_EQ(rk::contact_flux(1e4, 500, 500), 0);
}

TEST(HeatTransferLaws, RadiationIsStefanBoltzmannsAndItsConductanceBoundsItsSlope) {
  EXPECT_EQ(rk::radiation_flux(0.7, 400, 400), 0);
  // eps sigma (Ta^4 - T^4) at T = 2 Ta: -15 eps sigma Ta^4
  EXPECT_NEAR(rk::radiation_flux(0.5, 300, 600), -15 * 0.5 * 5.670374419e-8 * std::pow(300, 4), 1e-9);
  // the explicit step's bound: |q(T) - q(Ta)| <= h_r(T) |T - Ta| on both sides of Ta
  for (double T : {100.0, 250.0, 350.0, 800.0, 1500.0}) {
    const double slope = std::abs(rk::radiation_flux(0.8, 300, T) / (T - 300));
    EXPECT_LE(slope, rk::radiation_conductance(0.8, 300, T)) << T;
    EXPECT_GT(slope, 0.25 * rk::radiation_conductance(0.8, 300, T)) << T;  // and is not far above it
  }
}

TEST(BoundaryFaces, ABoxOfHexahedraHasItsSixFacesOutwardAndNothingInside) {
  const auto path = std::filesystem::temp_directory_path() / "rk_boundary_box.geo";
  std::ofstream(path) << "Point(1) = {0, 0, 0};\nl[] = Extrude {6, 0, 0} { Point{1}; Layers{3}; };\n"
                         "s[] = Extrude {0, 4, 0} { Line{l[1]}; Layers{2}; Recombine; };\n"
                         "v[] = Extrude {0, 0, 2} { Surface{s[1]}; Layers{1}; Recombine; };\n";
  const rk::VolumeMesh mesh = rk::mesh_cad({path.string(), 1.0, 2.0});
  const rk::BoundaryFaces faces = rk::boundary_faces(mesh);
  // 3 x 2 cells, one layer: 6 below, 6 above, 2 x 3 on the long sides, 2 x 2 on the ends
  ASSERT_EQ(faces.size(), 6u + 6u + 6u + 4u);
  double area = 0, sum[3] = {0, 0, 0};
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::int32_t* n = &faces.face_nodes[std::size_t(faces.face_offsets[f])];
    ASSERT_EQ(faces.face_offsets[f + 1] - faces.face_offsets[f], 4);
    auto x = [&](int a, int i) { return mesh.X[3 * std::size_t(n[a]) + i]; };
    const double d1[3] = {x(2, 0) - x(0, 0), x(2, 1) - x(0, 1), x(2, 2) - x(0, 2)};
    const double d2[3] = {x(3, 0) - x(1, 0), x(3, 1) - x(1, 1), x(3, 2) - x(1, 2)};
    const double a[3] = {0.5 * (d1[1] * d2[2] - d1[2] * d2[1]), 0.5 * (d1[2] * d2[0] - d1[0] * d2[2]),
                         0.5 * (d1[0] * d2[1] - d1[1] * d2[0])};
    double outward = 0;  // from the box's centre (3, 2, 1) to the face's centre, along its normal
    for (int i = 0; i < 3; ++i) {
      const double centre = 0.25 * (x(0, i) + x(1, i) + x(2, i) + x(3, i));
      outward += a[i] * (centre - (i == 0 ? 3.0 : i == 1 ? 2.0 : 1.0));
      sum[i] += a[i];
    }
    EXPECT_GT(outward, 0) << "face " << f << " points inward";
    area += std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  EXPECT_NEAR(area, 2 * (6 * 4 + 6 * 2 + 4 * 2), 1e-9);  // the box's surface
  for (double s : sum) EXPECT_NEAR(s, 0, 1e-9);           // a closed surface
}

}  // namespace
