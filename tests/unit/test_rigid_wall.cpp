// Rigid walls (solver/contact/die_contact.hpp): the upsetting eighth (geometry/upsetting, 2.5 mm
// spacing, 1 rank) with its die replaced by a fixed rigid wall at z = 10 mm, the billet's top, whose
// normal points down into the part.
// - The wall holds the material, not the coefficients: with one coefficient of the top face raised
//   through the wall, the particles in contact are exactly those whose X_I + u^h(X_I) is past it (u^h
//   evaluated here with the RK shape functions directly): its neighbours too, not it alone. A wall
//   that held the coefficients (as a kinematic wall on d_I would) meets one particle.
// - A rigid lift through the wall presses exactly the particles and points the lift carries past
//   it, each with k = s m / dt^2 times its depth, along the wall's normal; the wall's force along its
//   normal is their sum, and spread as N_J f it reaches the particles whole (partition of unity).
#include <gtest/gtest.h>

#include "contact/die_contact.hpp"
#include "material_above.hpp"
#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"
#include "source_dir.hpp"

namespace {

using rk::test::kSource;
constexpr double kTop = 10e-3;

struct WalledBillet {
  rk::Scene scene = walled();
  rk::Model md = one_rank_model(scene, {});

  static rk::Scene walled() {
    rk::Scene s = rk::load_scene(kSource + "/geometry/upsetting/scene.yaml", {{"discretization.spacing", "2.5e-3"}});
    s.dies.clear();
    s.time.cfl = s.default_cfl();  // as a scene without dies resolves it (the penalty's scale holds there)
    s.rigid_walls = {{"top", {0, 0, kTop}, {0, 0, -1}}};
    return s;
  }
};

TEST(RigidWall, HoldsTheMaterialAtTheParticlesNotTheirCoefficients) {
  const WalledBillet w;
  const rk::Model& md = w.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  const double dt = 1e-7, bump = 0.2e-3;
  std::size_t raised = md.n;
  for (std::size_t I = 0; I < md.n && raised == md.n; ++I)
    if (md.X[3 * I + 2] > kTop - 1e-9 && md.X[3 * I] > 4e-3 && md.X[3 * I + 1] > 4e-3) raised = I;
  ASSERT_LT(raised, md.n);
  st.u[3 * raised + 2] = bump;
  rk::DieContact contact(md, w.scene, {});
  contact.compute(md, st, 0.0, dt, dt);
  ASSERT_EQ(contact.totals().size(), 2u) << "the wall, then the symmetry planes";

  const AboveCount above = count_above(md, w.scene, st, kTop);
  ASSERT_TRUE(above.regular);
  ASSERT_EQ(above.coefficients, 1);
  ASSERT_GT(above.material, 1) << "the raised coefficient lifts the material around it through the wall";
  EXPECT_EQ(contact.totals()[0].contacts, above.material);
  EXPECT_GT(contact.wall_force(0), 0.0) << "the wall pushes the material back into the part";
}

TEST(RigidWall, ALiftThroughTheWallIsPushedBackAlongItsNormal) {
  const WalledBillet w;
  const rk::Model& md = w.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  const double lift = 0.8e-3, dt = 1e-7, s = w.scene.contact.penalty_scale;
  for (std::size_t I = 0; I < md.n; ++I) st.u[3 * I + 2] = lift;
  rk::DieContact contact(md, w.scene, {});
  const double bound = contact.compute(md, st, 0.0, dt, dt);
  const rk::DieTotals& wall = contact.totals()[0];

  const LiftedPast past = lifted_past(md, lift, kTop, s, dt);
  ASSERT_GT(past.particles, 0);
  ASSERT_GT(past.points, 0);
  EXPECT_EQ(wall.contacts, past.particles);
  EXPECT_EQ(wall.point_contacts, past.points);
  EXPECT_NEAR(contact.wall_force(0) / past.force, 1.0, 1e-9);
  EXPECT_NEAR(wall.force[2] / -past.force, 1.0, 1e-9) << "along the wall's normal, -z";
  EXPECT_NEAR(wall.max_penetration, lift, 1e-12);

  const rk::FixedScale scale = rk::FixedScale::for_bound(bound, 12);
  std::fill(st.partial.begin(), st.partial.end(), rk::Fixed(0));
  contact.add_to(md, st.partial, scale);
  double on_particles = 0;
  for (std::size_t I = 0; I < md.n; ++I) on_particles -= scale.real(st.partial[rk::kForceStride * I + 2]);
  EXPECT_NEAR(on_particles / wall.force[2], 1.0, 1e-9) << "sum_J N_J f = f";
}

}  // namespace
