// Gather: F_g = I + sum_I d_I (x) grad_X N_I(X_g) at every integration point (total Lagrangian),
// and the F-bar cell average of det F. After a reference update (rk/reference_update.hpp) the same
// gather on the displacement since the update, d_I - d_I^ref, with the shapes of the new reference.
#pragma once
#include <span>

#include "model.hpp"
#include "state.hpp"

namespace rk {

void compute_deformation_gradient(const Model& md, State& st);
// The same at the points of the listed cells only (multi-rate steps: the cells due this step).
void compute_deformation_gradient(const Model& md, State& st, std::span<const std::int32_t> cells);

// Integration point g's current position X_g + u^h(X_g) (the material's, from the reference point
// and the displacement since the last reference update, d_J - d_J^ref).
void point_position(const Model& md, const State& st, std::size_t g, double x[3]);

// u^h at owned constrained particle q's reference position (its row md.ebc_*), from t = 0:
// d_I^ref + sum_J N_J (d_J - d_J^ref) (d^ref = 0 before the first reference update).
void constrained_displacement(const Model& md, const State& st, std::size_t q, double uh[3]);

// The same at owned particle I from its row md.material_*.
void material_displacement(const Model& md, const State& st, std::size_t I, double uh[3]);

// v^h(X_I) = sum_J N_J(X_I) v_J at owned particle I (its row md.material_*), from the velocities v.
void material_velocity(const Model& md, const std::vector<double>& v, std::size_t I, double vh[3]);

// Owned particle I's material position X_I^ref + u^h(X_I) since the last update (its row md.material_*),
// the counterpart of point_position.
void material_position(const Model& md, const State& st, std::size_t I, double x[3]);

}  // namespace rk
