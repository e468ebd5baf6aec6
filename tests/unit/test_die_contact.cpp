// Die contact (solver/contact/die_contact.hpp) on the upsetting eighth (geometry/upsetting, 2.5 mm
// spacing, 1 rank), whose die's lower face is the plane z = 10 mm, the billet's top.
// - A rigid lift of the billet into the die: the particles and the integration points inside are
//   exactly those whose lifted positions are above the plane, each pressed by k = s m / dt^2 times
//   its depth (the points at X_g + u^h(X_g), which a translation moves like the particles), and the
//   points' forces, spread as N_J f, add up to the same total on the particles (partition of unity).
// - The lookups skipped while a slave is clear of the die find the same contacts, bitwise, as a
//   lookup of every slave at every step, through a non-uniform motion into a die that moves too
//   and across the symmetry plane x = 0, also where each contact is built over the last (a reference
//   update's: it takes over the dies' searches and the slaves' candidate lists; the sanitized build
//   reads the surfaces the searches hold).
// - The dies hold the material, not the coefficients: with one coefficient of the top face raised into
//   the die, the particles in contact are exactly those whose X_I + u^h(X_I) is past it (u^h
//   evaluated here with the RK shape functions directly): its neighbours too, not it alone.
// - The symmetry planes hold the same slaves as frictionless planes: a shift across x = 0 presses
//   exactly the particles and points the shift carries past it, with k times their depth along +x,
//   whichever sign the scene gives the plane's normal.
// - Coulomb friction on the same lifted billet (the die's face is the plane z = 10 mm, normal -z),
//   closed forms per slave with the normal force f_n = k d and the elastic stick of the same k loaded
//   by the slip v_t dt of each step: below mu f_n every slave sticks and the total is
//   -k dt v_t summed, twice that after a second step of the same slip, whatever mu; above it every
//   slave slips with mu f_n against the sliding direction, so the total tangential force is mu |F_z|
//   along -v_t; a die sliding over material at rest drags it along its own motion; sliding on at
//   mu f_n the friction work over a step is dt |F_t| times the sliding speed (>= 0), for either
//   direction, and a stick that only loads its spring dissipates nothing.
// - The sticks carried to another contact on the same slaves (a reference update's, a restart's)
//   load on exactly as if never moved; a stick naming a particle this rank does not hold is refused.
// - A spring held at its step's limit is damped on the approach, and its dashpot's dissipation counted.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>

#include "contact/die_contact.hpp"
#include "die_surface.hpp"
#include "error.hpp"
#include "material_above.hpp"
#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"
#include "source_dir.hpp"

namespace {

using rk::test::kSource;

struct Upsetting {
  rk::Scene scene = rk::load_scene(kSource + "/geometry/upsetting/scene.yaml", {{"discretization.spacing", "2.5e-3"}});
  std::vector<rk::DieSurface> dies{rk::mesh_die(scene.dies[0], scene.discretization.spacing)};
  rk::Model md = one_rank_model(scene, dies);
};

TEST(DieContact, ALiftIntoTheDieMeetsItAtTheParticlesAndThePoints) {
  const Upsetting u;
  const rk::Model& md = u.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  const double lift = 0.8e-3, top = 10e-3, dt = 1e-7, s = u.scene.penalty_scale_at_cfl();
  for (std::size_t I = 0; I < md.n; ++I) st.u[3 * I + 2] = lift;
  rk::DieContact contact(md, u.scene, u.dies);
  const double bound = contact.compute(md, st, 0.0, dt, dt);
  const rk::DieTotals& tot = contact.totals()[0];

  const LiftedPast past = lifted_past(md, lift, top, s, dt);
  ASSERT_GT(past.points, 0);
  EXPECT_EQ(tot.contacts, past.particles);
  EXPECT_EQ(tot.point_contacts, past.points);
  EXPECT_NEAR(tot.force[2] / -past.force, 1.0, 1e-9) << "the die pushes down";
  EXPECT_NEAR(tot.max_penetration, lift, 1e-12);

  const rk::FixedScale scale = rk::FixedScale::for_bound(bound, 12);  // resolution 2^-50 of the largest term
  std::fill(st.partial.begin(), st.partial.end(), rk::Fixed(0));
  contact.add_to(md, st.partial, scale);
  double on_particles = 0;
  for (std::size_t I = 0; I < md.n; ++I) on_particles -= scale.real(st.partial[rk::kForceStride * I + 2]);
  EXPECT_NEAR(on_particles / tot.force[2], 1.0, 1e-9) << "sum_J N_J f = f";
}

// A CFL changes the step, not the contact's stiffness: the same lift at time.cfl = 0.9, with its step
// 1.8x the default's (k = s m / dt_min^2, the scale taken at CFL 0.5 with dies), meets the die with the
// default's force; at 1.5 the spring's own bound m / dt^2 holds it instead (the dashpot of a spring held
// there, contact.damping, off: the die moves, and this is the stiffness alone).
TEST(DieContact, ACflChangesTheStepNotTheStiffness) {
  auto pressed = [](const char* cfl, double dt) {
    Upsetting u;
    u.scene = rk::load_scene(kSource + "/geometry/upsetting/scene.yaml",
                             {{"discretization.spacing", "2.5e-3"}, {"time.cfl", cfl}, {"contact.damping", "0"}});
    rk::State st = rk::State::initial(u.md, std::array<double, 9>{}.data(), std::array<double, 9>{}.data());
    for (std::size_t I = 0; I < u.md.n; ++I) st.u[3 * I + 2] = 0.8e-3;
    rk::DieContact contact(u.md, u.scene, u.dies);
    contact.compute(u.md, st, 0.0, dt, dt);
    return contact.totals()[0].force[2];
  };
  const double dt = 1e-7, f = pressed("0.5", dt);
  EXPECT_NEAR(pressed("0.9", 1.8 * dt) / f, 1.0, 1e-12);
  EXPECT_NEAR(pressed("1.5", 3.0 * dt) / f, 1.0 / (0.25 * 9.0), 1e-12) << "at most m / dt^2";
}

TEST(DieContact, SkippedLookupsFindTheSameContactsAsLookingUpEverySlave) {
  const Upsetting u;
  const rk::Model& md = u.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  auto kept = std::make_unique<rk::DieContact>(md, u.scene, u.dies);
  const double dt = 3e-6;
  std::int64_t touched = 0, crossed = 0;
  for (int n = 0; n < 400; ++n) {  // the material sways (up to 0.8 mm, unevenly) while the die comes down 1.1 mm
    const double t = n * dt;
    if (n % 50 == 49) kept = std::make_unique<rk::DieContact>(md, u.scene, u.dies, kept.get());
    for (std::size_t I = 0; I < md.n; ++I) {
      const double* X = &md.X[3 * I];
      st.u[3 * I] = 8e-4 * std::sin(t / 4e-5) * X[2] / 10e-3;  // past the points nearest x = 0 (0.53 mm)
      st.u[3 * I + 2] = 0.3e-3 * (0.6 + 0.4 * std::cos(X[0] / 3e-3 + t / 1e-4));
      st.v[3 * I] = 1.0, st.v[3 * I + 2] = -0.5;
    }
    rk::DieContact fresh(md, u.scene, u.dies);  // looks every slave up at its first call
    kept->compute(md, st, t, dt, dt);
    fresh.compute(md, st, t, dt, dt);
    for (std::size_t k = 0; k < kept->totals().size(); ++k) {  // the die, then the symmetry planes
      const rk::DieTotals &a = kept->totals()[k], &b = fresh.totals()[k];
      ASSERT_EQ(a.contacts, b.contacts) << "step " << n << ", obstacle " << k;
      ASSERT_EQ(a.point_contacts, b.point_contacts) << "step " << n << ", obstacle " << k;
      for (int i = 0; i < 3; ++i) ASSERT_EQ(a.force[i], b.force[i]) << "step " << n << ", obstacle " << k;
      ASSERT_EQ(a.max_penetration, b.max_penetration) << "step " << n << ", obstacle " << k;
    }
    touched += kept->totals()[0].point_contacts;
    crossed += kept->totals()[1].contacts + kept->totals()[1].point_contacts;
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
  contact.compute(md, st, 0.0, dt, dt);

  const AboveCount above = count_above(md, u.scene, st, top);
  ASSERT_TRUE(above.regular);
  ASSERT_EQ(above.coefficients, 1);
  ASSERT_GT(above.material, 1) << "the raised coefficient lifts the material around it into the die";
  EXPECT_EQ(contact.totals()[0].contacts, above.material);
}

TEST(DieContact, SymmetryPlanesHoldTheMaterialThatCrossesThem) {
  const Upsetting u;
  const rk::Model& md = u.md;
  const double zero[9] = {};
  rk::State st = rk::State::initial(md, zero, zero);
  const double shift = 0.8e-3, dt = 1e-7, s = u.scene.penalty_scale_at_cfl();  // across x = 0, not into the die
  for (std::size_t I = 0; I < md.n; ++I) st.u[3 * I] = -shift;
  rk::DieContact contact(md, u.scene, u.dies);
  const double bound = contact.compute(md, st, 0.0, dt, dt);
  rk::Scene flipped = u.scene;  // a plane given with its normal away from the part holds the same side
  for (auto& plane : flipped.symmetry_planes)
    for (double& c : plane.normal) c = -c;
  rk::DieContact same(md, flipped, u.dies);
  same.compute(md, st, 0.0, dt, dt);
  ASSERT_EQ(contact.totals().size(), 2u) << "the die, then the planes";
  const rk::DieTotals& planes = contact.totals()[1];

  // The particles on x = 0 are the plane's own, held both ways by the essential BCs, not by the plane.
  double expected = 0, deepest = 0;
  std::int64_t particles = 0, points = 0, own = 0;
  for (std::size_t I = 0; I < md.n; ++I) {
    if (md.X[3 * I] == 0) ++own;
    else if (md.X[3 * I] - shift < 0) ++particles, expected += s * md.mass[I] / (dt * dt) * (shift - md.X[3 * I]);
  }
  for (std::size_t g = 0; g < md.m; ++g)
    if (md.point_X[3 * g] - shift < 0) {
      ++points, expected += s * md.material_at(g).density * md.weight[g] / (dt * dt) * (shift - md.point_X[3 * g]);
      deepest = std::max(deepest, shift - md.point_X[3 * g]);
    }
  ASSERT_GT(points, 0);
  ASSERT_GT(own, 0);
  EXPECT_NEAR(contact.symmetry_depth(), deepest, 1e-15) << "the health check's depth";
  EXPECT_GE(contact.deepest_particle(md), 0);
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
  contact.add_to(md, st.partial, scale);
  double on_particles = 0;
  for (std::size_t I = 0; I < md.n; ++I) on_particles -= scale.real(st.partial[rk::kForceStride * I]);
  EXPECT_NEAR(on_particles / planes.force[0], 1.0, 1e-9) << "sum_J N_J f = f";
}

// The billet lifted 0.8 mm into the die with every coefficient at velocity v (the field is v
// everywhere: the rows sum to one), for the friction tests: the slaves in contact with their
// depths and masses.
struct Lifted {
  static constexpr double lift = 0.8e-3, top = 10e-3, dt = 1e-7;
  struct Slave {
    double depth, mass;
  };
  std::vector<Slave> slaves;
  double depth_min = 1e300, depth_max = 0;

  explicit Lifted(const Upsetting& u) {
    const rk::Model& md = u.md;
    for (std::size_t I = 0; I < md.n; ++I)
      if (md.X[3 * I + 2] + lift > top) slaves.push_back({md.X[3 * I + 2] + lift - top, md.mass[I]});
    for (std::size_t g = 0; g < md.m; ++g)
      if (md.point_X[3 * g + 2] + lift > top)
        slaves.push_back({md.point_X[3 * g + 2] + lift - top, md.material_at(g).density * md.weight[g]});
    for (const auto& s : slaves) depth_min = std::min(depth_min, s.depth), depth_max = std::max(depth_max, s.depth);
  }
  static rk::State state(const rk::Model& md, const double v[3]) {
    const double zero[9] = {};
    rk::State st = rk::State::initial(md, zero, zero);
    for (std::size_t I = 0; I < md.n; ++I)
      for (int i = 0; i < 3; ++i) st.u[3 * I + i] = i == 2 ? lift : 0.0, st.v[3 * I + i] = v[i];
    return st;
  }
  // sum over the slaves of k dt = s m / dt: the stick's force per unit sliding speed after one step
  double stick_rate(double penalty_scale) const {
    double sum = 0;
    for (const auto& s : slaves) sum += penalty_scale * s.mass / dt;
    return sum;
  }
  double normal_force(double penalty_scale) const {
    double sum = 0;
    for (const auto& s : slaves) sum += penalty_scale * s.mass / (dt * dt) * s.depth;
    return sum;
  }
};

rk::Scene with_friction(const Upsetting& u, double mu) {
  rk::Scene scene = u.scene;
  scene.dies[0].friction = mu;
  return scene;
}

// A spring held at its step's limit (the step twice the one its stiffness keeps to: k = m / dt^2) takes
// the dashpot 2 xi m / dt on the material's normal velocity relative to the die (contact_laws.hpp):
// material moving with the die feels k d alone; material closing on it at w more feels k d + c w per
// slave, and the step's dissipation, sum c w^2 dt, is in friction_work; at the step the stiffness keeps
// to, no dashpot. Closed forms per slave on the lifted billet (the die's face z = 10 mm, normal -z).
TEST(DieContact, ASpringHeldAtItsStepsLimitDampsTheApproach) {
  const Upsetting u;
  const Lifted lifted(u);
  const double xi = u.scene.contact.damping, dt_min = Lifted::dt, dt = 2 * dt_min, s = u.scene.penalty_scale_at_cfl();
  ASSERT_GT(s * dt * dt, dt_min * dt_min);
  ASSERT_EQ(xi, 0.2);
  const std::array<double, 3>& dir = u.scene.dies[0].motion.direction;
  rk::DieContact probe(u.md, u.scene, u.dies);
  const double rate = probe.rate(0, 0.0);
  ASSERT_GT(rate, 0.0);
  double spring = 0, dashpot = 0, below = 0;  // sums over the slaves of m d / dt^2, 2 xi m / dt, s m d / dt_min^2
  for (const auto& sl : lifted.slaves)
    spring += sl.mass * sl.depth / (dt * dt), dashpot += 2 * xi * sl.mass / dt, below += s * sl.mass * sl.depth / (dt_min * dt_min);
  for (const double w : {0.0, 0.5, 2.0}) {  // closing speed on the die (m/s)
    const double v[3] = {rate * dir[0], rate * dir[1], rate * dir[2] + w};
    rk::State st = Lifted::state(u.md, v);
    rk::DieContact contact(u.md, u.scene, u.dies);
    contact.compute(u.md, st, 0.0, dt, dt_min);
    const rk::DieTotals& tot = contact.totals()[0];
    ASSERT_EQ(std::size_t(tot.contacts + tot.point_contacts), lifted.slaves.size());
    EXPECT_NEAR(-tot.force[2] / (spring + dashpot * w), 1.0, 1e-9) << "closing at " << w << " m/s";
    contact.account(u.md, st, st.v, dt, 0.0);
    if (w > 0) EXPECT_NEAR(tot.friction_work / (dashpot * w * w * dt), 1.0, 1e-9) << "closing at " << w << " m/s";
    else EXPECT_LT(std::abs(tot.friction_work), dashpot * 1e-12 * dt) << "moving with the die: round-off (a closing speed under 1 um/s)";
    rk::DieContact short_step(u.md, u.scene, u.dies);
    short_step.compute(u.md, st, 0.0, dt_min, dt_min);
    EXPECT_NEAR(-short_step.totals()[0].force[2] / below, 1.0, 1e-9) << "no dashpot at the stiffness's own step";
  }
}

TEST(DieContact, FrictionsStickLoadsWithTheSlipWithinMuFn) {
  const Upsetting u;
  const Lifted lifted(u);
  const double mu = 0.12, s = u.scene.penalty_scale_at_cfl(), dt = Lifted::dt;
  ASSERT_GT(lifted.depth_min, 0.0);
  // a slave sticks while k (slip) <= mu k d, i.e. while it has slid under mu d: two steps of a
  // quarter of the shallowest's
  const double vx = 0.25 * mu * lifted.depth_min / dt;
  const double v[3] = {vx, 0, 0};
  const rk::State st = Lifted::state(u.md, v);
  const double expected = -lifted.stick_rate(s) * vx;
  for (double m : {mu, 0.5}) {  // stuck: the force does not depend on mu
    rk::DieContact contact(u.md, with_friction(u, m), u.dies);
    for (int step = 1; step <= 2; ++step) {
      contact.compute(u.md, st, 0.0, dt, dt);
      const rk::DieTotals& tot = contact.totals()[0];
      ASSERT_EQ(std::size_t(tot.contacts + tot.point_contacts), lifted.slaves.size());
      EXPECT_NEAR(tot.force[2] / -lifted.normal_force(s), 1.0, 1e-9) << "the normal force is unchanged";
      EXPECT_NEAR(tot.force[0] / (step * expected), 1.0, 1e-9) << "mu " << m << ", step " << step << ": k times the slip so far";
      EXPECT_NEAR(tot.force[1], 0.0, 1e-9 * std::abs(expected));
      EXPECT_LT(std::abs(tot.force[0]), m * std::abs(tot.force[2])) << "within the friction cone";
    }
  }
  rk::DieContact frictionless(u.md, u.scene, u.dies);  // the scene's mu = 0: no tangential force
  frictionless.compute(u.md, st, 0.0, dt, dt);
  EXPECT_EQ(frictionless.totals()[0].force[0], 0.0);
  EXPECT_EQ(frictionless.totals()[0].force[1], 0.0);
  EXPECT_TRUE(frictionless.stick_rows().empty());
}

// every slave slips in its first step when k dt v > mu k d for the deepest: 4x that
double slipping_speed(const Lifted& lifted, double mu) { return 4 * mu * lifted.depth_max / Lifted::dt; }

TEST(DieContact, FrictionSlipsAtMuFnAgainstTheSlidingDirection) {
  const Upsetting u;
  const Lifted lifted(u);
  const double mu = 0.12, s = u.scene.penalty_scale_at_cfl(), dt = Lifted::dt;
  const double speed = slipping_speed(lifted, mu);
  const double dir[3] = {0.6, -0.8, 0};  // a sliding direction off the axes
  const double v[3] = {speed * dir[0], speed * dir[1], 0};
  const rk::State st = Lifted::state(u.md, v);
  rk::DieContact contact(u.md, with_friction(u, mu), u.dies);
  contact.compute(u.md, st, 0.0, dt, dt);
  const rk::DieTotals& tot = contact.totals()[0];
  const double fn = lifted.normal_force(s);
  ASSERT_EQ(std::size_t(tot.contacts + tot.point_contacts), lifted.slaves.size());
  EXPECT_NEAR(tot.force[2] / -fn, 1.0, 1e-9);
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(tot.force[i] / (-mu * fn * dir[i]), 1.0, 1e-9) << "component " << i << ": mu f_n against v_t";
  EXPECT_LT(mu * fn, lifted.stick_rate(s) * speed) << "below what the stick would take";
}

TEST(DieContact, ADieSlidingOverMaterialAtRestDragsItAlong) {
  const Upsetting u;
  const Lifted lifted(u);
  const double mu = 0.12, s = u.scene.penalty_scale_at_cfl(), dt = Lifted::dt;
  rk::Scene scene = with_friction(u, mu);
  const double speed = slipping_speed(lifted, mu);  // slip everywhere, as above
  scene.dies[0].motion = rk::DieMotion{};  // the die moves along +y over its own face's plane
  scene.dies[0].motion.direction = {0, 1, 0}, scene.dies[0].motion.speed = speed;
  const double rest[3] = {0, 0, 0};
  const rk::State st = Lifted::state(u.md, rest);
  rk::DieContact contact(u.md, scene, u.dies);
  contact.compute(u.md, st, 0.0, dt, dt);
  const rk::DieTotals& tot = contact.totals()[0];
  const double fn = lifted.normal_force(s);
  ASSERT_EQ(std::size_t(tot.contacts + tot.point_contacts), lifted.slaves.size());
  EXPECT_NEAR(tot.force[1] / (mu * fn), 1.0, 1e-9) << "the relative velocity is the material's less the die's";
  EXPECT_NEAR(tot.force[0], 0.0, 1e-9 * fn);
}

TEST(DieContact, FrictionWorkIsTheForceTimesTheSlidingSpeedAndTheStickStoresItsLoad) {
  const Upsetting u;
  const Lifted lifted(u);
  const double mu = 0.12, s = u.scene.penalty_scale_at_cfl(), dt = Lifted::dt;
  for (double sign : {1.0, -1.0}) {
    // sliding on at mu f_n (the second step: the stick already at the cap): the work is dt |F_t| v
    const double slip = slipping_speed(lifted, mu), v[3] = {sign * slip, 0, 0};
    rk::State st = Lifted::state(u.md, v);
    rk::DieContact contact(u.md, with_friction(u, mu), u.dies);
    contact.compute(u.md, st, 0.0, dt, dt);
    contact.compute(u.md, st, 0.0, dt, dt);
    const double ft = std::abs(contact.totals()[0].force[0]);
    ASSERT_GT(ft, 0.0);
    contact.account(u.md, st, st.v, dt, 0.0);
    EXPECT_GE(contact.totals()[0].friction_work, 0.0);
    EXPECT_NEAR(contact.totals()[0].friction_work / (dt * ft * slip), 1.0, 1e-9) << "sign " << sign;
    // a stick loaded in one step by sliding that stopped by the step's end (its mean speed half): the
    // work dt |F_t| v / 2 = k dt^2 v^2 / 2 is what its spring now holds, and nothing is dissipated
    const double stick = 0.5 * mu * lifted.depth_min / dt, w[3] = {sign * stick, 0, 0};
    rk::State stuck = Lifted::state(u.md, w);
    rk::DieContact held(u.md, with_friction(u, mu), u.dies);
    held.compute(u.md, stuck, 0.0, dt, dt);
    const std::vector<double> v_old = stuck.v;
    for (std::size_t k = 0; k < stuck.v.size(); k += 3) stuck.v[k] = 0;
    held.account(u.md, stuck, v_old, dt, 0.0);
    const double work = 0.5 * dt * std::abs(held.totals()[0].force[0]) * stick;
    EXPECT_NEAR(held.totals()[0].friction_work / work, 0.0, 1e-9) << "sign " << sign;
    // the spring energy holds it, beside the normal springs' k d^2 / 2
    double normal = 0;
    for (const auto& sl : lifted.slaves) normal += 0.5 * s * sl.mass / (dt * dt) * sl.depth * sl.depth;
    EXPECT_NEAR((held.totals()[0].spring_energy - normal) / work, 1.0, 1e-9) << "sign " << sign;
  }
}

TEST(DieContact, CarriedSticksLoadOnAsIfNeverMoved) {
  const Upsetting u;
  const Lifted lifted(u);
  const double mu = 0.12, dt = Lifted::dt;
  const double v[3] = {0.2 * mu * lifted.depth_min / dt, 0.1 * mu * lifted.depth_min / dt, 0};
  const rk::State st = Lifted::state(u.md, v);
  rk::DieContact first(u.md, with_friction(u, mu), u.dies), second(u.md, with_friction(u, mu), u.dies);
  first.compute(u.md, st, 0.0, dt, dt);
  const std::vector<double> rows = first.stick_rows();
  ASSERT_EQ(rows.size(), rk::DieContact::kStickValues * lifted.slaves.size());
  second.set_stick_rows(rows, "test");
  first.compute(u.md, st, 0.0, dt, dt);
  second.compute(u.md, st, 0.0, dt, dt);
  EXPECT_EQ(first.stick_rows(), second.stick_rows());
  EXPECT_EQ(first.totals()[0].force[0], second.totals()[0].force[0]);
  std::vector<double> bad = rows;
  bad[0] = 1e9;  // a particle no rank holds
  try {
    second.set_stick_rows(bad, "rank_0000.h5");
    ADD_FAILURE() << "a stick on a particle this rank does not hold was taken";
  } catch (const rk::Error& e) {
    EXPECT_NE(std::string(e.what()).find("rank_0000.h5: a friction stick names particle 1000000000"), std::string::npos) << e.what();
  }
}

}  // namespace
