// Heat conduction through the part, and heat exchange through its surface, on the RK discretization:
// the temperature is a field T^h(x) = sum_I N_I(x) T_I with a coefficient T_I per particle, and
// energy balance in weak form with a lumped capacity gives, per particle,
//   C_I dT_I/dt = - sum_g w_g grad N_I(X_g) . (k J C^-1 grad T^h)(X_g)      conduction, on the reference
//                 + sum_f A_f q_f / n_f                                        surface faces f with I a node
//                 + sum_g N_I(X_g) w_g rho0 c dT_g/dt                          the plastic work's heat
//                 + the part's share of the friction's heat at I as a contact slave
// with C_I = rho0 c sum_g w_g N_I(X_g) (so sum_I C_I T_I is the part's heat content exactly), q_f the
// flux into the part at the face's temperature (thermal/heat_transfer_laws.hpp: contact with a die
// where the face touches one, else convection and radiation to the ambient; none on a symmetry plane)
// and n_f the face's node count. The particles on a temperature face are held at its temperature.
//
// With a specific heat table c(T) the shapes carry the enthalpy per reference volume e = rho0 h(T),
// h = int_0^T c: e^h(x) = sum_I N_I(x) e(T_I), the temperature T^h = e^-1(e^h) and its gradient
// grad e^h / (rho0 c(T^h)); the update is V_I de_I/dt = (the same right-hand side) with V_I =
// sum_g w_g N_I(X_g), so the heat content sum_I V_I e_I = sum_g w_g e(T_g) is kept exactly as well.
//
// Explicit: the temperature's stable step (Gershgorin's bound on the conductance matrix over the
// capacities) is much longer than the mechanical one for metals, so the thermal update runs only when
// the next mechanical step would carry it past that, every k steps (k is not fixed: it follows both
// steps), capped by thermal.max_steps_per_update. Between updates the points heat adiabatically by
// their plastic work (material/stress_update.cpp), kept as State::heat_pending and spread to the
// particles at the next update. Where the thermal step is the shorter, an update takes several
// thermal sub-steps. Sums are fixed point (parallel/fixed_point.hpp): the temperatures do not depend
// on the rank count.
#pragma once
#include <optional>
#include <vector>

#include "contact/die_contact.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "parallel/overlap_exchange.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

class HeatTransfer {
 public:
  // On the current reference (rebuilt after each reference update): the capacities, the temperature
  // faces' particles and the faces on symmetry planes. Collective; throws rk::Error naming a
  // particle whose capacity is not positive.
  HeatTransfer(const Model& md, const Scene& scene, const Comm& comm);

  // t = 0: T_I the initial temperature at X_I (initial_conditions, its regions; a temperature face's
  // particles its temperature), the points' T^h, the first stable step. Collective.
  void start(const Model& md, State& st, DieContact& dies, const Comm& comm);

  // After a reference update (the shape functions and so the capacities changed): the coefficients
  // of the points' temperatures (their pending heat, and the particles' friction heat, included) projected onto the new shapes, lumped,
  // C_I T_I = rho0 c sum_g w_g N_I(X_g) T_g, so the part's heat content sum_I C_I T_I = rho0 c
  // sum_g w_g T_g is kept exactly; the points' T^h follow. Collective.
  void reproject(const Model& md, State& st, const Comm& comm);

  // Whether the mechanical step dt from t^n would carry the temperature past its stable step (or past
  // the cap on mechanical steps per update): then update() runs first.
  bool due(const State& st, double dt) const;

  // Advances the temperature from the last update to t^n (sub-stepped where the stable step is
  // shorter), spreads the points' pending heat, sets the points' T^h and the next stable step.
  // Collective.
  void update(const Model& md, State& st, DieContact& dies, const Comm& comm);

 private:
  struct FaceState {
    double area = 0, T = 0;
    int die = -1;  // the die it touches; -1: the ambient; -2: none (a symmetry plane or a wall)
  };
  // The faces' areas, temperatures and what they touch at time t.
  void classify_faces(const Model& md, const State& st, const DieContact& dies, double t);
  // The particles' net heat inflow over dt (J) into heat_, fixed-point summed over the ranks, and
  // each particle's conductance bound (W/K) into bound_ when `bound` is set; the heat the faces
  // give the dies and the ambient booked.
  void assemble(const Model& md, State& st, DieContact& dies, double dt, bool pending, bool bound, const Comm& comm);
  double stable_step(const Model& md, const Comm& comm) const;  // from bound_ (after an assemble with it)
  FixedScale lump(const Model& md, const std::vector<double>* values, const std::vector<double>* extra, const Comm& comm);
  void settle(const Model& md, State& st);
  // The particles' field values: T_I, or with a specific heat table e(T_I) (into enthalpy_).
  const std::vector<double>& field_values(const Model& md, const State& st);
  void hold_faces(State& st) const;

  const Scene& scene_;
  std::vector<double> capacity_;  // C_I (J/K); with a specific heat table V_I (m^3)
  std::vector<std::int32_t> fixed_particles_;
  std::vector<double> fixed_temperature_;
  int headroom_ = 0;
  std::optional<OverlapExchange> exchange_;
  // scratch, sized once
  std::vector<double> conductance_;  // per point: w_g J_ref k J C^-1 (6, Voigt)
  std::vector<double> flux_;         // per point: that times grad T^h (3)
  std::vector<double> spread_;       // per point: |conductance| sum_J |grad N_J|, for the Gershgorin bound
  std::vector<FaceState> faces_;
  std::vector<Fixed> partial_;       // 2 per particle: heat, conductance bound
  std::vector<double> heat_, bound_;
  std::vector<double> enthalpy_, point_enthalpy_;  // e(T_I) and e(T_g), J/m^3: with a specific heat table
  // of the shape functions on this reference: |grad N| per term; per point their sum and the largest |N|
  std::vector<double> grad_norm_, grad_norm_sum_, N_max_;
};

}  // namespace rk
