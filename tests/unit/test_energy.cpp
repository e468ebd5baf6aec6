// The energy balance (solver/energy.hpp): the two kinetic energies a rank sums from the half-step
// velocities, the central difference's own in the balance, and a scale that keeps the largest energy put in.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "die_surface.hpp"
#include "energy.hpp"
#include "material_above.hpp"
#include "scene.hpp"
#include "state.hpp"
#include "source_dir.hpp"

namespace {

// On the upsetting eighth (2.5 mm, 1 rank), v^{n-1/2} = a and v^{n+1/2} = b on every particle: the
// kinetic energy is M |(a + b) / 2|^2 / 2 and the central difference's M a . b / 2, M the part's mass.
// With b = -a (a particle at the turn of its swing) the first is 0 and the second -M |a|^2 / 2.
TEST(EnergyError, TheRanksKineticEnergiesFromTheTwoHalfStepVelocities) {
  const rk::Scene scene = rk::load_scene(rk::test::kSource + "/geometry/upsetting/scene.yaml",
                                         {{"discretization.spacing", "2.5e-3"}});
  const std::vector<rk::DieSurface> dies{rk::mesh_die(scene.dies[0], scene.discretization.spacing)};
  const rk::Model md = one_rank_model(scene, dies);
  rk::State st = rk::State::initial(md, std::array<double, 9>{}.data(), std::array<double, 9>{}.data());
  const double a[3] = {1.0, -2.0, 0.5}, b[3] = {3.0, 1.0, -1.0};
  std::vector<double> v_old(st.v.size());
  double M = 0;
  for (std::size_t I = 0; I < md.n; ++I) {
    if (md.owned[I]) M += md.mass[I];
    for (int i = 0; i < 3; ++i) v_old[3 * I + i] = a[i], st.v[3 * I + i] = b[i];
  }
  rk::Energies e = rk::rank_energies(md, st, v_old);
  EXPECT_NEAR(e.kinetic / (0.5 * M * (4.0 + 0.25 + 0.0625)), 1.0, 1e-12);  // (a + b) / 2 = (2, -0.5, -0.25)
  EXPECT_NEAR(e.kinetic_step / (0.5 * M * (3.0 - 2.0 - 0.5)), 1.0, 1e-12);  // a . b = 0.5
  for (std::size_t I = 0; I < md.n; ++I)
    for (int i = 0; i < 3; ++i) st.v[3 * I + i] = -a[i];
  e = rk::rank_energies(md, st, v_old);
  EXPECT_NEAR(e.kinetic, 0.0, 1e-15);
  EXPECT_NEAR(e.kinetic_step / (-0.5 * M * 5.25), 1.0, 1e-12);
}

// One mass on a linear spring, stepped as the solver steps the particles (v^{n+1/2} = v^{n-1/2} - dt k
// u^n / m, u^{n+1} = u^n + dt v^{n+1/2}) at omega dt = 1.8, near the limit 2. With the kinetic energy
// m v^{n-1/2} v^{n+1/2} / 2 the balance holds to round-off; with m vbar^2 / 2 it is off by m dt^2 a^2 / 8,
// (omega dt)^2 / 8 = 40 % of the energy at the spring's stretch.
TEST(EnergyError, TheCentralDifferencesOwnKineticEnergyBalancesALinearOscillator) {
  const double m = 2.0, k = 50.0, omega = std::sqrt(k / m), dt = 1.8 / omega, v0 = 3.0;
  double u = 0, v_old = v0, v = v0, worst = 0, worst_vbar = 0, scale = 0;
  const double kinetic0 = 0.5 * m * v0 * v0;
  for (int n = 0; n < 1000; ++n) {
    v_old = v;
    v -= dt * k * u / m;  // v^{n+1/2} from the force at u^n
    rk::Energies e;
    const double vbar = 0.5 * (v_old + v);
    e.kinetic = 0.5 * m * vbar * vbar, e.kinetic_step = 0.5 * m * v_old * v;
    e.internal = 0.5 * k * u * u;
    worst = std::max(worst, rk::energy_error(e, kinetic0, scale));
    worst_vbar = std::max(worst_vbar, std::abs(e.kinetic + e.internal - kinetic0) / kinetic0);
    u += dt * v;
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(worst_vbar, 0.3) << "the mean velocity's kinetic energy is what the balance must not take";
}

// A load put in and taken off again (the thermal strain's work of a bar that rings as it cools) leaves
// the scale at the largest energy it put in: the same imbalance reads the same error.
TEST(EnergyError, TheScaleKeepsTheLargestEnergyPutIn) {
  double scale = 0;
  rk::Energies e;
  e.external = 1.0, e.internal = 1.001;
  EXPECT_NEAR(rk::energy_error(e, 0.0, scale), 1e-3, 1e-12);
  e.external = 0.01, e.internal = 0.011;
  EXPECT_NEAR(rk::energy_error(e, 0.0, scale), 1e-3, 1e-12) << "not 0.1 of the energy held now";
  EXPECT_DOUBLE_EQ(scale, 1.0);
  // the thermal strain's work sets it too (it is in the internal energy, with the stored energy it made)
  e.external = 0, e.thermal = -2.0, e.internal = 0.002;
  EXPECT_NEAR(rk::energy_error(e, 0.0, scale), 1e-3, 1e-12);
  EXPECT_DOUBLE_EQ(scale, 2.0);
}

}  // namespace
