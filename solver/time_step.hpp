// Stable time step from the CURRENT deformation, taken every step (it shortens as the part is
// compressed). In total-Lagrangian RKPM the stiffness M^-1 K depends on the particles' motion only
// through F at the integration points (grad_x N = grad_X N F^-1), so the step is measured there, not
// from how close particles come (their coefficients may crowd without stiffening anything):
//   dt = CFL * min over cells of h0_c * min_{g in c} sigma_min(F_g) / c_c,
// h0_c the cell's shortest edge at t = 0 (after a reference update the contact's step takes the
// shorter of that and its edge on the new reference, Model::cell_h_reference, and h0_c is at most
// max(1, reference_updates.step_growth x 0.9 / CFL) times that: the step grows at most so far past the
// contact's step at the default CFL),
// sigma_min the smallest principal stretch, and
// c_c^2 = (K + 4G/3) / rho the dilatational wave speed at the current density rho = rho0 / Jbar;
// with bulk viscosity each point's term shrinks by its factor (material/bulk_viscosity.hpp).
// Why: docs/decisions.md, "Stable time step from the deformation at the integration points".
#pragma once
#include <vector>

#include "model.hpp"
#include "state.hpp"

namespace rk {

struct StableStep {
  double dt;
  std::size_t cell;  // the cell that sets it
};

// `damped`: with bulk viscosity's factors (the step); without them, the undamped estimate. `first`: a
// cell to measure first (the last step's; the same step whatever it is, only sooner). `on_reference`:
// set to the step on Model::cell_h_reference (after a reference update, the contact's; infinite before
// one), found in the same pass.
StableStep stable_time_step(const Model& md, const State& st, double cfl, bool damped = true,
                            std::size_t first = std::size_t(-1), double* on_reference = nullptr);

// Every cell's own stable step, CFL times the least over its points (with bulk viscosity's factors), into
// dt_cell (resized to the cells), for the classes of multi-rate steps (subcycles.hpp): the largest
// k <= levels with 2^k dt <= dt_cell[c] is the cell's own step's. The step itself where it sets that
// class; where the cheap lower bounds hold the class, where they and stretch_ceiling put the point in
// one class, or where the cell is at the least class already, its points are not measured further.
void cell_time_steps(const Model& md, const State& st, double cfl, double dt, int levels, std::vector<double>& dt_cell);

// At or above every cell's own stable step (stretch_ceiling at one point of each cell). Below twice the
// smallest step, every cell takes the smallest (multi-rate steps need no classes then).
double cell_time_step_ceiling(const Model& md, const State& st, double cfl);

// Smallest principal stretch of F: sqrt of the smallest eigenvalue of C = F^T F (closed form);
// det F as the kinematics computed it (State::J).
double smallest_stretch(const double F[9], double detF);

// Gershgorin's lower bound on the smallest eigenvalue of C = F^T F (may be negative: no bound).
double gershgorin_floor(const double F[9]);

// sqrt(min_i C_ii), C = F^T F: at or above the smallest principal stretch (a Rayleigh quotient).
double stretch_ceiling(const double F[9]);

}  // namespace rk
