// Bulk viscosity (von Neumann and Richtmyer's quadratic term, Landshoff's linear term, with
// LS-DYNA's defaults 1.5 and 0.06): where the material is compressed, the pressure
//   q = rho l |e| (C_quadratic l |e| + C_linear c),   e = tr D = d(ln J)/dt < 0 (0 in expansion)
// is added to the stress, which spreads a shock over a few cells instead of letting it ring, and
// the stable step shrinks to l / (Q + sqrt(Q^2 + c^2)), Q = C_linear c + C_quadratic l |e|.
// l is the particle spacing about the cell (the mean of its particles' h_I) scaled by J^(1/3): the
// method's resolution, the same whichever cells integrate it (a tetrahedron's shortest edge would
// make q depend on the mesh); c the dilatational wave speed, rho the current density; with F-bar J
// is the cell's (one q per cell, as its pressure), else the point's. The rate
// is that of the step just taken, ln(J^n / J^{n-1}) / dt^{n-1/2}. The work q does, the trapezoid
// of q over the volume change, is dissipated: State::viscous_work, part of the internal energy.
#pragma once
#include <span>

#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

// Sizes the arrays (empty when both coefficients are 0: nothing is computed or stored).
void init_bulk_viscosity(const Model& md, State& st, const Scene::BulkViscosity& k);

// After the deformation gradient at t^n: q and the step factor of every point, and the work of q.
void update_bulk_viscosity(const Model& md, State& st, const Scene::BulkViscosity& k);
// The same at the listed cells only, each over its own increment since its last update, t -
// State::cell_t_last (multi-rate steps).
void update_bulk_viscosity(const Model& md, State& st, const Scene::BulkViscosity& k, std::span<const std::int32_t> cells);

}  // namespace rk
