#include "health.hpp"

#include <cmath>
#include <sstream>

#include "rk/kinematics.hpp"

namespace rk {

std::string describe_particle(const Model& md, const State& st, std::int32_t I) {
  // the material's position X_I + u^h(X_I) for an owned particle; else X_I + d_I
  double u[3] = {st.u[3 * I], st.u[3 * I + 1], st.u[3 * I + 2]};
  if (md.material_offsets[I + 1] > md.material_offsets[I]) material_displacement(md, st, std::size_t(I), u);
  std::ostringstream s;
  s << "particle " << md.global_id[I] << " at (" << md.X[3 * I] + u[0] << ", " << md.X[3 * I + 1] + u[1] << ", "
    << md.X[3 * I + 2] + u[2] << ") m";
  return s.str();
}

void HealthChecks::after_reduction(const Model& md, const State& st, const DieContact& dies, const StepLimits& limits,
                                   const StableStep& stable, const StressHealth& stress, bool healthy, const Comm& comm,
                                   const WriteLastFrame& last_frame) const {
  const auto& health = scene_.health;
  if (limits.dt < health.min_dt_ratio * scales_.dt0) {  // a cell has collapsed: the run would never end
    last_frame();
    std::ostringstream why;
    why << "the stable time step collapsed to " << stable.dt << " s (" << stable.dt / scales_.dt0
        << " of the initial step) at step " << st.step << ", t = " << st.t << " s, in the cell of "
        << describe_particle(md, st, md.cell_nodes[md.cell_node_offsets[stable.cell]])
        << " (last frame written); refine the spacing there";
    comm.check(stable.dt > limits.dt, why.str());
  }
  if (limits.symmetry_depth > health.max_symmetry_depth) {  // the material broke through a symmetry plane
    last_frame();
    const std::int32_t I = dies.deepest_particle(md);
    std::ostringstream why;
    if (I >= 0)
      why << "the material near " << describe_particle(md, st, I) << " is " << dies.symmetry_depth()
          << " m past a symmetry plane (health.max_symmetry_depth = " << health.max_symmetry_depth
          << " spacings) at step " << st.step << ", t = " << st.t
          << " s (last frame written); the state is not physical: refine the spacing or reduce time.cfl";
    comm.check(I < 0 || dies.symmetry_depth() / scales_.h_min <= health.max_symmetry_depth, why.str());
  }
  if (limits.unhealthy) {  // a rank is unhealthy: show the user the state, then stop every rank
    std::ostringstream why;
    if (stress.pressure_stop)
      why << "rank " << comm.rank() << ": the pressure near " << describe_particle(md, st, md.nbr[md.nbr_offsets[stress.point]])
          << " is " << stress.pressure << " Pa, " << stress.pressure_ratio << " times rho0 c_L v_max + sigma_y = "
          << std::abs(stress.pressure) / stress.pressure_ratio << " Pa there (health.max_pressure_ratio = "
          << health.max_pressure_ratio << ", v_max the fastest start or tool), at step " << st.step << ", t = " << st.t
          << " s: the state is not physical; refine the spacing or reduce time.cfl";
    else if (!stress.ok)
      why << "rank " << comm.rank() << ": det F = " << stress.J << " at step " << st.step << ", t = " << st.t
          << " s, near " << describe_particle(md, st, md.nbr[md.nbr_offsets[stress.point]])
          << (stress.J > 0 ? " (the material's volume ratio; outside (0.5, 2) no solid metal is, the state is not physical)"
                           : "");
    else
      why << "rank " << comm.rank() << ": non-finite forces at step " << st.step << ", t = " << st.t << " s";
    last_frame();
    comm.check(healthy, why.str() + " (last frame written)");
  }
}

void HealthChecks::after_history(const Model& md, const State& st, const DieContact& dies, double energy_error,
                                 bool started, const Comm& comm, const WriteLastFrame& last_frame) const {
  if (dies.size() > 0) escaped_particle(md, st, dies, comm, last_frame);
  // Runaway check; skipped in the start-up, where the energies are still tiny and the first-order
  // work of freshly engaged contacts dominates their ratio.
  if (energy_error > scene_.health.max_energy_error && started) energy_runaway(md, st, energy_error, comm, last_frame);
}

// A particle that has left the box of the part and the dies: the run went wrong.
void HealthChecks::escaped_particle(const Model& md, const State& st, const DieContact& dies, const Comm& comm,
                                    const WriteLastFrame& last_frame) const {
  double lo[3], hi[3];
  dies.box(scales_.part_lo, scales_.part_hi, st.t, lo, hi);
  std::size_t out = md.n;
  for (std::size_t I = 0; I < md.n && out == md.n; ++I) {
    if (!md.owned[I]) continue;
    double uh[3];  // where the material at the particle is (the dies hold u^h(X_I), not d_I)
    material_displacement(md, st, I, uh);
    for (int d = 0; d < 3; ++d)
      if (!(md.X[3 * I + d] + uh[d] >= lo[d] && md.X[3 * I + d] + uh[d] <= hi[d])) out = I;
  }
  double escaped = out < md.n ? 1.0 : 0.0;
  comm.max(&escaped, 1);
  if (escaped == 0) return;
  last_frame();
  std::ostringstream why;
  if (out < md.n)
    why << describe_particle(md, st, std::int32_t(out)) << " has left the box of the part and the dies (" << lo[0] << ", "
        << lo[1] << ", " << lo[2] << ") - (" << hi[0] << ", " << hi[1] << ", " << hi[2] << ") m at step " << st.step
        << ", t = " << st.t << " s (last frame written)";
  comm.check(out == md.n, why.str());
}

void HealthChecks::energy_runaway(const Model& md, const State& st, double energy_error, const Comm& comm,
                                  const WriteLastFrame& last_frame) const {
  last_frame();
  // Where the energy grows: an unstable mode of the discretization moves the coefficients in a
  // pattern the field does not carry, so it shows as |v_I - v^h(X_I)|, largest at the mode.
  double worst = -1;
  std::int32_t where = -1;
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    double vh[3], d2 = 0;
    material_velocity(md, st.v, I, vh);
    for (int i = 0; i < 3; ++i) d2 += (st.v[3 * I + i] - vh[i]) * (st.v[3 * I + i] - vh[i]);
    if (d2 > worst) worst = d2, where = std::int32_t(I);
  }
  double largest = worst;
  comm.max(&largest, 1);
  std::ostringstream why;
  why << "energy error " << energy_error << " exceeds health.max_energy_error = " << scene_.health.max_energy_error
      << " at step " << st.step << ", t = " << st.t << " s (last frame written)";
  // a velocity the field does not carry, over half the fastest start or tool: nothing that started
  // the run explains it, an unstable mode
  const bool mode = std::sqrt(std::max(largest, 0.0)) > 0.5 * scales_.v_start;
  if (where >= 0 && mode)
    why << "; the velocity the field does not carry is largest at " << describe_particle(md, st, where) << " ("
        << std::sqrt(std::max(worst, 0.0)) << " m/s): an unstable mode there; reduce time.cfl";
  else if (where >= 0)
    why << "; the field carries the particles' velocities (no unstable mode: at most "
        << std::sqrt(std::max(largest, 0.0)) << " m/s against the start's " << scales_.v_start
        << " m/s): a start too sudden (a die from rest to full speed: ramp it up with motion.curve), a contact "
           "too coarse, or a bound below the method's error (health.max_energy_error)";
  comm.check(where < 0 || worst < largest, why.str());
  comm.check(false, why.str());
}

}  // namespace rk
