// Offline data (changes only at a reference update, never checkpointed): the local particles, the
// rank's integration points with their neighbour lists and RK shape-function values and gradients
// stored in CSR aligned with the neighbour columns, the cells (for F-bar and the time step), the
// constraints.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "material/j2_plasticity.hpp"
#include "scene.hpp"
#include "subdomain.hpp"

namespace rk {

// A material as the step uses it.
struct Solid {
  J2Params law;
  double density = 0;       // kg/m^3, times the mass-scaling factor
  double wave_modulus = 0;  // K + 4G/3, for the dilatational wave speed
  // the dilatational wave speed squared at volume ratio J (the 1e-12 floor keeps it real until the
  // stress update's health check stops a collapsed cell)
  double wave_speed2(double J) const { return wave_modulus * std::max(J, 1e-12) / density; }
  static Solid of(const J2Params& law, double density) { return {law, density, law.bulk + 4.0 / 3.0 * law.shear}; }
};

struct Model {
  int rank = 0, ranks = 1;
  // particles (local = owned + overlap), SoA
  std::size_t n = 0;
  std::vector<std::int64_t> global_id;
  std::vector<double> X, mass, volume, spacing;  // X: initial position (t = 0)
  // Xr: the reference positions the shape functions are built on; X until a reference update
  // (rk/reference_update.hpp), then the particles' positions X + u at the last update
  std::vector<double> Xr;
  std::vector<double> spacing0;  // h_I at t = 0 (spacing: on the reference configuration)
  std::vector<std::uint8_t> owned, surface, body;  // body: subdomain.hpp's body_of(flags)
  std::vector<std::int32_t> owner;  // the rank that owns each local particle
  // essential BCs (boundary/constraints.cpp): each local particle's constrained directions e_k,
  // orthonormal, CSR per particle; the value g_k(t) = coef * stroke(t) of prescribed face
  // `value_face` (-1: g = 0); the face a reaction is reported under (-1: a symmetry plane)
  std::vector<std::int32_t> constraint_offsets;
  std::vector<double> constraint_dirs;  // 3 per direction
  std::vector<double> constraint_coef;
  std::vector<std::int32_t> constraint_value_face, constraint_face;
  // the owned constrained particles and their rows N_J(X_I) (local J, CSR), for the exact method
  // and for measuring the error of the nodal one
  std::vector<std::int32_t> ebc_particles, ebc_offsets, ebc_cols;
  std::vector<double> ebc_N;
  std::vector<double> face_particles;  // owned particles per face (all_faces numbering)
  // where the material at each owned particle is: its row N_J(X_I) (local J, CSR over the local
  // particles; empty for the others; {I: 1} where the moment matrix is singular), for contact at
  // u^h(X_I) (contact/die_contact.hpp) and to show u^h(X_I) in the results
  std::vector<std::int32_t> material_offsets, material_cols;
  std::vector<double> material_N;

  // integration points, SoA; neighbours and shape data in CSR (point -> columns)
  std::size_t m = 0;
  std::vector<double> weight;   // reference volume at t = 0 (m^3)
  std::vector<double> point_X;  // 3 per point: its position in the reference configuration (Xr)
  std::vector<std::int64_t> nbr_offsets;  // 64-bit: a rank's points times their neighbours may pass 2^31
  std::vector<std::int32_t> nbr;
  std::vector<double> N, dN;   // N_I(X_g); dN_I/dX (3 per column)
  std::vector<double> dN_max;  // max_I |grad N_I(X_g)|, bounds the force contributions

  // cells: their points are contiguous, cell_points[c]..cell_points[c+1]
  std::size_t cells = 0;
  std::vector<std::int64_t> cell_global_id;
  std::vector<std::int32_t> cell_points, cell_node_offsets, cell_nodes;
  // shortest edge at t = 0, for the stable time step (after a reference update at most
  // reference_updates.step_growth times cell_h_reference)
  std::vector<double> cell_h0;
  // after a reference update, the shorter of the t = 0 edge and the edge on the new reference: the
  // contact's step (time_step.hpp); empty before the first
  std::vector<double> cell_h_reference;

  // points whose supports hold a shared particle (their forces are sent first) and the others,
  // whose work overlaps the messages
  std::vector<std::int32_t> boundary_points, interior_points;

  // the part's boundary faces of this rank's cells (CSR, local particles, counter-clockwise from
  // outside) and the local cell each bounds
  std::vector<std::int32_t> surface_face_offsets, surface_face_nodes, surface_face_cell;

  // overlap maps (Wang et al. 2007, Fig. 3)
  std::vector<std::int32_t> neighbour_ranks;
  std::vector<std::vector<std::int32_t>> overlap;

  std::vector<DieSurface> dies;  // rigid die surfaces at t = 0

  // The materials: [0] the part's (and a body's without its own), then the bodies' own in the order of
  // geometry.bodies; the index of each cell's and each point's (a cell never spans two bodies)
  std::vector<Solid> materials;
  std::vector<std::uint8_t> cell_material, point_material;
  const Solid& material_of_cell(std::size_t c) const { return materials[cell_material[c]]; }
  const Solid& material_at(std::size_t g) const { return materials[point_material[g]]; }
  double mass_scaling = 1;  // density factor applied to reach time.mass_scaling_dt
  // heating by plastic work: dT = taylor_quinney dW_p / heat_capacity, with the material's own
  // rho0 c (J/(m^3 K), never mass-scaled); 0 without temperature. With a specific heat table c(T),
  // heat_capacity is rho0 c at the table's first point and capacity_at / enthalpy / temperature_of
  // follow the table (the enthalpy per reference volume rho0 h(T), h = int_0^T c).
  double heat_capacity = 0, taylor_quinney = 0;
  PiecewiseLinear specific_heat_table;
  double mass_density = 0;  // rho0, not mass-scaled
  bool tabled_heat() const { return !specific_heat_table.empty(); }
  double capacity_at(double T) const { return tabled_heat() ? mass_density * specific_heat_table.at(T) : heat_capacity; }
  double enthalpy(double T) const { return tabled_heat() ? mass_density * specific_heat_table.integral(T) : heat_capacity * T; }
  double temperature_of(double e) const {
    return tabled_heat() ? specific_heat_table.inverse_integral(e / mass_density) : e / heat_capacity;
  }
  // The thermal strain from the uniform initial temperature T0 (K): the stress-free stretch
  // 1 + alpha (T - T0), or (rho(T0) / rho(T))^(1/3) from a density table. A region that starts at
  // another temperature starts with its thermal strain, as a part heated locally from a uniform state.
  double thermal_expansion = 0, initial_temperature = 0;
  PiecewiseLinear density_table;
  bool thermal_strain() const { return thermal_expansion > 0 || !density_table.empty(); }
  double thermal_stretch(double T) const {
    return density_table.empty() ? linear_thermal_stretch(T)
                                 : std::cbrt(density_table.at(initial_temperature) / density_table.at(T));
  }
  template <class Real>  // a double, or a Lane of points (material/stress_update.cpp)
  Real linear_thermal_stretch(Real T) const {
    return 1 + thermal_expansion * (T - initial_temperature);
  }
  bool damage_cockcroft_latham = false, damage_brozzo = false, damage_oyane = false;  // the criteria the scene asks for
  double oyane_a = 0;                                                                  // Oyane's constant
  bool fbar = true;
  bool green_strain = false;  // the stress update measures the Green strain (the scene's reference updates ask for it)
};

// The body of cell c: its nodes' (a cell never spans two bodies).
inline int cell_body(const Model& md, std::size_t c) {
  return md.body[std::size_t(md.cell_nodes[std::size_t(md.cell_node_offsets[c])])];
}

// Builds the model from this rank's subdomain: neighbour search and shape functions at the points.
// Throws rk::Error naming the point if a moment matrix is singular. `initial_X` (3 per local
// particle): the t = 0 positions when sub.X is an updated reference configuration. `previous`: a
// model whose neighbour lists and shape functions are no longer read (a reference update's), their
// storage taken over for the new ones (memory already touched, one set of them held, not two).
Model build_model(const Subdomain& sub, const Scene& scene, const std::vector<double>* initial_X = nullptr,
                  Model* previous = nullptr);

// Quasi-static forming in explicit time: multiplies the density (masses and wave speed) by `factor`.
void scale_mass(Model& md, double factor);

// One material for every cell and point of `md` (its cells and points counted): for models built by hand.
void single_material(Model& md, const J2Params& law, double density);

}  // namespace rk
