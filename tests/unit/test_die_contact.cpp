// Die contact (solver/contact/die_contact.hpp) on the upsetting eighth (geometry/upsetting, 2.5 mm
// spacing, 1 rank), whose die's lower face is the plane z = 10 mm, the billet's top.
// - A rigid lift of the billet into the die: the particles and the integration points inside are
//   exactly those whose lifted positions are above the plane, each pressed by k = s m / dt^2 times
//   its depth (the points at X_g + u^h(X_g), which a translation moves like the particles), and the
//   points' forces, spread as N_J f, add up to the same total on the particles (partition of unity).
// - The lookups skipped while a slave is clear of the die find the same contacts, bitwise, as a
//   lookup of every slave at every step, through a non-uniform motion into a die that moves too
//   and across the symmetry plane x = 0.
// - The dies hold the material, not the coefficients: with one coefficient of the top face raised into
//   the die, the particles in contact are exactly those whose X_I + u^h(X_I) is past it (u^h
//   evaluated here with the RK shape functions directly): its neighbours too, not it alone.
// - The symmetry planes hold the same slaves as frictionless planes: a shift across x = 0 presses
//   exactly the particles and points the shift carries past it, with k times their depth along +x,
//   whichever sign the scene gives the plane's normal.
#include <gtest/gtest.h>

#include <cmath>

#include "cad_mesh.hpp"
#include "contact/die_contact.hpp"
#include "die_surface.hpp"
#include "discretize.hpp"
#include "local_shapes.hpp"
#include "model.hpp"
#include "partition.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace {

const std::string kSource = RK_SOURCE_DIR;

struct Upsetting {
  rk::Scene scene = rk::load_scene(kSource + "/geometry/upsetting/scene.yaml", {{"discretization.spacing", "2.5e-3"}});
  std::vector<rk::DieSurface> dies{rk::mesh_die(scene.dies[0], scene.discretization.spacing)};
  rk::Model md = model();

  rk::Model model() const {
    const rk::VolumeMesh mesh = rk::mesh_cad({scene.geometry.cad, scene.geometry.unit, scene.discretization.spacing});
    const rk::Discretization disc = rk::discretize(mesh, scene.discretization.gauss_order);
    const auto cell_rank = rk::partition_cells(mesh, disc, 1, "metis-kway");
    return rk::build_model(rk::build_subdomains({mesh, disc, cell_rank, 1, scene.discretization.dilation, scene.prep_hash, dies})[0],
                           scene);
  }
};

TEST(DieContact, ALiftIntoTheDieMeetsItAtTheParticlesAndThePoints) {
  const Upsetting u;
  const rk::Model& md = u.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  const double lift = 0.8e-3, top = 10e-3, dt = 1e-7, s = u.scene.contact.penalty_scale;
  for (std::size_t I = 0; I < md.n; ++I) st.u[3 * I + 2] = lift;
  rk::DieContact contact(md, u.scene, u.dies);
  const double bound = contact.compute(md, st, 0.0, dt);
  const rk::DieTotals& tot = contact.totals()[0];

  double expected = 0;
  std::int64_t particles = 0, points = 0;
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.X[3 * I + 2] + lift > top) ++particles, expected += s * md.mass[I] / (dt * dt) * (md.X[3 * I + 2] + lift - top);
  for (std::size_t g = 0; g < md.m; ++g)
    if (md.point_X[3 * g + 2] + lift > top)
      ++points, expected += s * md.density * md.weight[g] / (dt * dt) * (md.point_X[3 * g + 2] + lift - top);
  ASSERT_GT(points, 0);
  EXPECT_EQ(tot.contacts, particles);
  EXPECT_EQ(tot.point_contacts, points);
  EXPECT_NEAR(tot.force[2] / -expected, 1.0, 1e-9) << "the die pushes down";
  EXPECT_NEAR(tot.max_penetration, lift, 1e-12);

  const rk::FixedScale scale = rk::FixedScale::for_bound(bound, 12);  // resolution 2^-50 of the largest term
  std::fill(st.partial.begin(), st.partial.end(), rk::Fixed(0));
  contact.add_to(md, st, scale);
  double on_particles = 0;
  for (std::size_t I = 0; I < md.n; ++I) on_particles -= scale.real(st.partial[3 * I + 2]);
  EXPECT_NEAR(on_particles / tot.force[2], 1.0, 1e-9) << "sum_J N_J f = f";
}

TEST(DieContact, SkippedLookupsFindTheSameContactsAsLookingUpEverySlave) {
  const Upsetting u;
  const rk::Model& md = u.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  rk::DieContact kept(md, u.scene, u.dies);
  const double dt = 3e-6;
  std::int64_t touched = 0, crossed = 0;
  for (int n = 0; n < 400; ++n) {  // the material sways (up to 0.3 mm, unevenly) while the die comes down 1.1 mm
    const double t = n * dt;
    for (std::size_t I = 0; I < md.n; ++I) {
      const double* X = &md.X[3 * I];
      st.u[3 * I] = 2e-4 * std::sin(t / 4e-5) * X[2] / 10e-3;
      st.u[3 * I + 2] = 0.3e-3 * (0.6 + 0.4 * std::cos(X[0] / 3e-3 + t / 1e-4));
      st.v[3 * I] = 1.0, st.v[3 * I + 2] = -0.5;
    }
    rk::DieContact fresh(md, u.scene, u.dies);  // looks every slave up at its first call
    kept.compute(md, st, t, dt);
    fresh.compute(md, st, t, dt);
    for (std::size_t k = 0; k < kept.totals().size(); ++k) {  // the die, then the symmetry planes
      const rk::DieTotals &a = kept.totals()[k], &b = fresh.totals()[k];
      ASSERT_EQ(a.contacts, b.contacts) << "step " << n << ", obstacle " << k;
      ASSERT_EQ(a.point_contacts, b.point_contacts) << "step " << n << ", obstacle " << k;
      for (int i = 0; i < 3; ++i) ASSERT_EQ(a.force[i], b.force[i]) << "step " << n << ", obstacle " << k;
      ASSERT_EQ(a.max_penetration, b.max_penetration) << "step " << n << ", obstacle " << k;
    }
    touched += kept.totals()[0].point_contacts;
    crossed += kept.totals()[1].contacts + kept.totals()[1].point_contacts;
  }
  EXPECT_GT(touched, 1000) << "the motion must reach the die";
  EXPECT_GT(crossed, 1000) << "the sway must cross the plane x = 0";
}

TEST(DieContact, TheDiesHoldTheMaterialAtTheParticlesNotTheirCoefficients) {
  const Upsetting u;
  const rk::Model& md = u.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  const double top = 10e-3, dt = 1e-7, bump = 0.2e-3;  // one coefficient of the top face raised
  std::size_t raised = md.n;
  for (std::size_t I = 0; I < md.n && raised == md.n; ++I)
    if (md.X[3 * I + 2] > top - 1e-9 && md.X[3 * I] > 4e-3 && md.X[3 * I + 1] > 4e-3) raised = I;
  ASSERT_LT(raised, md.n);
  st.u[3 * raised + 2] = bump;
  rk::DieContact contact(md, u.scene, u.dies);
  contact.compute(md, st, 0.0, dt);

  const rk::LocalShapes shapes(md.X, md.volume, md.spacing, u.scene);
  std::int64_t material = 0, coefficients = 0;
  std::vector<std::int32_t> cols;
  std::vector<double> N, dN;
  for (std::size_t I = 0; I < md.n; ++I) {
    cols.clear(), N.clear(), dN.clear();
    ASSERT_TRUE(shapes.append(&md.X[3 * I], cols, N, dN).regular);
    double uz = 0;
    for (std::size_t k = 0; k < cols.size(); ++k) uz += N[k] * st.u[3 * std::size_t(cols[k]) + 2];
    material += md.X[3 * I + 2] + uz > top;
    coefficients += md.X[3 * I + 2] + st.u[3 * I + 2] > top;
  }
  ASSERT_GT(material, 0);
  ASSERT_EQ(coefficients, 1);
  ASSERT_GT(material, 1) << "the raised coefficient lifts the material around it into the die";
  EXPECT_EQ(contact.totals()[0].contacts, material);
}

TEST(DieContact, SymmetryPlanesHoldTheMaterialThatCrossesThem) {
  const Upsetting u;
  const rk::Model& md = u.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  const double shift = 0.8e-3, dt = 1e-7, s = u.scene.contact.penalty_scale;  // across x = 0, not into the die
  for (std::size_t I = 0; I < md.n; ++I) st.u[3 * I] = -shift;
  rk::DieContact contact(md, u.scene, u.dies);
  const double bound = contact.compute(md, st, 0.0, dt);
  rk::Scene flipped = u.scene;  // a plane given with its normal away from the part holds the same side
  for (auto& plane : flipped.symmetry_planes)
    for (double& c : plane.normal) c = -c;
  rk::DieContact same(md, flipped, u.dies);
  same.compute(md, st, 0.0, dt);
  ASSERT_EQ(contact.totals().size(), 2u) << "the die, then the planes";
  const rk::DieTotals& planes = contact.totals()[1];

  double expected = 0;
  std::int64_t particles = 0, points = 0;
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.X[3 * I] - shift < 0) ++particles, expected += s * md.mass[I] / (dt * dt) * (shift - md.X[3 * I]);
  for (std::size_t g = 0; g < md.m; ++g)
    if (md.point_X[3 * g] - shift < 0) ++points, expected += s * md.density * md.weight[g] / (dt * dt) * (shift - md.point_X[3 * g]);
  ASSERT_GT(points, 0);
  EXPECT_EQ(contact.totals()[0].contacts + contact.totals()[0].point_contacts, 0) << "nothing reaches the die";
  EXPECT_EQ(planes.contacts, particles);
  EXPECT_EQ(planes.point_contacts, points);
  EXPECT_NEAR(planes.force[0] / expected, 1.0, 1e-9) << "pushed back along +x";
  EXPECT_NEAR(planes.force[1], 0.0, 1e-9 * expected);
  EXPECT_EQ(same.totals()[1].contacts, particles);
  EXPECT_EQ(same.totals()[1].point_contacts, points);
  EXPECT_EQ(same.totals()[1].force[0], planes.force[0]) << "the normal's sign comes from the part's side";

  const rk::FixedScale scale = rk::FixedScale::for_bound(bound, 12);
  std::fill(st.partial.begin(), st.partial.end(), rk::Fixed(0));
  contact.add_to(md, st, scale);
  double on_particles = 0;
  for (std::size_t I = 0; I < md.n; ++I) on_particles -= scale.real(st.partial[3 * I]);
  EXPECT_NEAR(on_particles / planes.force[0], 1.0, 1e-9) << "sum_J N_J f = f";
}

}  // namespace
