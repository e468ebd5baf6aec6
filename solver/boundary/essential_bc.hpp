// Essential boundary conditions applied to the velocities each step (Wang et al. 2007, Sec. 2), so that the
// displacements u^{n+1} = u^n + dt v^{n+1/2} meet e_k . u = g_k(t^{n+1}) at the constrained particles:
//   nodal           on the coefficients d_I of each particle (fast; approximate, since RK shape
//                   functions do not interpolate: u^h(X_I) != d_I);
//   transformation  on u^h(X_I) = sum_J N_J(X_I) d_J, exactly (to round-off): the mass-weighted
//                   least change of the velocities that satisfies all constraints together, with the
//                   constraint system factorized once (constraint_factor.hpp).
// Parallel: every rank holds the whole (small) constraint system, gathered and factorized once in
// global-id order; each step the owners of the constrained particles compute their residuals, one
// allreduce assembles them, and every rank solves and corrects its local particles, so every rank
// count gives bitwise the same answer.
#pragma once
#include <memory>
#include <vector>

#include "boundary/constraint_factor.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

class EssentialBcs {
 public:
  EssentialBcs(const Model& md, const Scene& scene, const Comm& comm);

  // dt > 0: the velocities that bring the displacements onto g(t_next) in one step; dt = 0: the
  // velocities meet the rates dg/dt (initial conditions). With dt > 0 the reactions and the work of
  // the constraint impulses (at the mid-step velocity, from v_old = v^{n-1/2}) are recorded.
  void apply(const Model& md, State& st, double t_next, double dt, double dt_avg, const std::vector<double>& v_old);

  // Puts local particle I's position x (3) onto its faces at time t: e_k . (x - X_I) = g_k(t).
  void project(const Model& md, std::size_t I, double t, double* x) const;

  // This rank's largest |e_k . u^h(X_I) - g_k(t)| over its owned constrained particles (m).
  double max_error(const Model& md, const State& st, double t) const;

  // Reaction force on the modeled part per reported face (fixed, then prescribed), this rank's
  // share, 3 per face (N), from the last apply.
  const std::vector<double>& reactions() const { return reaction_; }
  // This rank's work of the last apply's impulses: at a history row the energy balance counts half
  // of it (the kinetic energy there is taken at the mid-step velocity).
  double step_work() const { return step_work_; }
  std::int64_t constraints() const { return rows_; }
  bool exact() const { return factor_ != nullptr; }

 private:
  double value(const Model& md, std::int32_t k, double t, bool rate) const;
  void apply_nodal(const Model& md, State& st, double t_next, double dt, double dt_avg, const std::vector<double>& v_old);
  void apply_exact(const Model& md, State& st, double t_next, double dt, double dt_avg, const std::vector<double>& v_old);

  const Comm& comm_;
  std::vector<DieMotion> motions_;  // of the prescribed faces
  std::vector<double> reaction_;
  double step_work_ = 0;
  std::int64_t rows_ = 0;  // constrained directions over all ranks

  // transformation: the global particles' directions, this rank's rows and column corrections
  std::unique_ptr<ConstraintFactor> factor_;
  std::vector<double> dirs_;                    // 3 per global row, rows of a particle contiguous
  std::vector<std::int32_t> particle_rows_;     // global constrained particle p: rows [.. p], [.. p+1])
  std::vector<std::int32_t> own_first_row_;     // per md.ebc_particles entry: its first global row
  std::vector<std::int32_t> fix_offsets_, fix_particle_;  // per local particle J: (p, N_J(X_p)) entries
  std::vector<double> fix_N_, rho_, lambda_, w_;
};

}  // namespace rk
