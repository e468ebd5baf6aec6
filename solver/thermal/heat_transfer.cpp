#include "thermal/heat_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rk/internal_force.hpp"
#include "rk/surface_faces.hpp"
#include "thermal/heat_transfer_laws.hpp"

namespace rk {
namespace {

// The explicit Euler step's margin under its limit 2 / lambda_max (lambda_max bounded by Gershgorin).
constexpr double kSafety = 0.9;

// T^h at point g from the particles' field values (their temperatures, or with a specific heat table
// their enthalpies, whose field's temperature it is).
// (The even and the odd terms in sums of their own here and in the assembly's gradient: one chain of
// multiply-adds waits on each add's latency, two halve the wait.)
double point_temperature(const Model& md, const std::vector<double>& field, std::size_t g) {
  const std::int64_t k1 = md.nbr_offsets[g + 1];
  double v = 0, odd = 0;
  auto k = md.nbr_offsets[g];
  for (; k + 1 < k1; k += 2)
    v += md.N[std::size_t(k)] * field[std::size_t(md.nbr[k])], odd += md.N[std::size_t(k) + 1] * field[std::size_t(md.nbr[k + 1])];
  if (k < k1) v += md.N[std::size_t(k)] * field[std::size_t(md.nbr[k])];
  v += odd;
  return md.tabled_heat() ? md.temperature_of(v) : v;
}

// w_g J_ref k(T_g) J C^-1 at point g (Voigt xx, yy, zz, xy, yz, zx): the conductivity pulled back to the
// reference, times the point's reference volume.
void pulled_back_conductance(const Model& md, const State& st, const Material& mat, std::size_t g, double K[6]) {
  const double k = mat.conductivity_at(st.temperature[g]);  // at the point's temperature
  const double* F = &st.F[9 * g];
  const double cof[9] = {F[4] * F[8] - F[5] * F[7], F[5] * F[6] - F[3] * F[8], F[3] * F[7] - F[4] * F[6],
                         F[2] * F[7] - F[1] * F[8], F[0] * F[8] - F[2] * F[6], F[1] * F[6] - F[0] * F[7],
                         F[1] * F[5] - F[2] * F[4], F[2] * F[3] - F[0] * F[5], F[0] * F[4] - F[1] * F[3]};
  const double J = F[0] * cof[0] + F[1] * cof[1] + F[2] * cof[2];
  // F^-1 = cof^T / J, so J C^-1 = J F^-1 F^-T = cof^T cof / J
  auto c = [&](int a, int b) { return (cof[a] * cof[b] + cof[3 + a] * cof[3 + b] + cof[6 + a] * cof[6 + b]) / J; };
  const double scale = md.weight[g] * (st.J_ref.empty() ? 1.0 : st.J_ref[g]) * k;  // w_g J_ref: its reference volume
  K[0] = scale * c(0, 0), K[1] = scale * c(1, 1), K[2] = scale * c(2, 2);
  K[3] = scale * c(0, 1), K[4] = scale * c(1, 2), K[5] = scale * c(2, 0);
}

// A bound on the largest eigenvalue of the symmetric K (Voigt as above), |K d| <= it |d|: the smaller of
// its Frobenius norm and its largest row sum, both bounds on the spectral norm. An isotropic k I gives
// k (the row sum) where the Frobenius norm gives sqrt(3) k, so the stable step is that much longer.
double spectral_bound(const double K[6]) {
  const double frobenius =
      std::sqrt(K[0] * K[0] + K[1] * K[1] + K[2] * K[2] + 2 * (K[3] * K[3] + K[4] * K[4] + K[5] * K[5]));
  const double rows = std::max({std::abs(K[0]) + std::abs(K[3]) + std::abs(K[5]), std::abs(K[3]) + std::abs(K[1]) + std::abs(K[4]),
                                std::abs(K[5]) + std::abs(K[4]) + std::abs(K[2])});
  return std::min(frobenius, rows);
}

// The mean of face f's nodes' temperature coefficients.
double face_temperature(const Model& md, const State& st, std::size_t f) {
  const auto k0 = md.surface_face_offsets[f], k1 = md.surface_face_offsets[f + 1];
  double T = 0;
  for (auto k = k0; k < k1; ++k) T += st.particle_temperature[std::size_t(md.surface_face_nodes[std::size_t(k)])];
  return T / double(k1 - k0);
}

}  // namespace

HeatTransfer::HeatTransfer(const Model& md, const Scene& scene, const Comm& comm)
    : scene_(scene), conductance_(6 * md.m), flux_(3 * md.m), spread_(md.m), partial_(2 * md.n), heat_(md.n), bound_(md.n),
      enthalpy_(md.tabled_heat() ? md.n : 0), point_enthalpy_(md.tabled_heat() ? md.m : 0), grad_norm_sum_(md.m),
      N_max_(md.m) {
  headroom_ = force_headroom(md, 1, 64, comm);  // a column per point and particle; faces: at most 64 per particle
  exchange_.emplace(md, 2);
  // C_I = rho0 c sum_g w_g N_I(X_g) (with a specific heat table V_I = sum_g w_g N_I(X_g)), summed over the ranks
  const FixedScale scale = lump(md, nullptr, nullptr, comm);
  capacity_.resize(md.n);
  std::int64_t bad = -1;
  for (std::size_t I = 0; I < md.n; ++I) {
    capacity_[I] = scale.real(partial_[2 * I]);
    if (md.owned[I] && !(capacity_[I] > 0) && bad < 0) bad = md.global_id[I];
  }
  comm.check(bad < 0, "particle " + std::to_string(bad) +
                          ": its heat capacity sum_g w_g N_I(X_g) rho c is not positive (a particle its integration "
                          "points barely reach); refine the discretization or raise discretization.dilation");

  // the particles on each temperature face, identified at t = 0 (within 1e-6 of a spacing of the plane)
  for (const TemperatureFace& f : scene.thermal.fixed_faces) {
    double held = 0;
    for (std::size_t I = 0; I < md.n; ++I) {
      double d = 0;
      for (int i = 0; i < 3; ++i) d += (md.X[3 * I + i] - f.point[i]) * f.normal[i];
      if (std::abs(d) <= 1e-6 * md.spacing[I]) {
        fixed_particles_.push_back(std::int32_t(I)), fixed_temperature_.push_back(f.temperature);
        held += md.owned[I];
      }
    }
    comm.sum(&held, 1);
    comm.check(held > 0, "thermal.fixed_faces '" + f.name + "': no particle of the part lies on its plane");
  }
  faces_.resize(md.surface_face_offsets.empty() ? 0 : md.surface_face_offsets.size() - 1);
  // what the assembly needs of the shape functions, fixed on this reference: each term's |grad N| (a
  // square root per term and sub-step was a third of the assembly's time where the bound is refreshed at
  // every update), and per point their sum and the largest |N|: 8 bytes a neighbour, +6 % of a heat
  // slab's peak memory per point (3957 -> 4197 bytes), for conducting scenes only
  grad_norm_.resize(std::size_t(md.nbr_offsets[md.m]));
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) {
      const double* d = &md.dN[3 * std::size_t(k)];
      const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      grad_norm_[std::size_t(k)] = norm;
      grad_norm_sum_[g] += norm;
      N_max_[g] = std::max(N_max_[g], std::abs(md.N[std::size_t(k)]));
    }
}

void HeatTransfer::start(const Model& md, State& st, DieContact& dies, const Comm& comm) {
  st.particle_temperature.resize(md.n);
  for (std::size_t I = 0; I < md.n; ++I) st.particle_temperature[I] = scene_.initial.temperature_at(&md.X[3 * I]);
  st.surface_heat.assign(md.n, 0.0);
  st.heat_pending.assign(md.m, 0.0);
  settle(md, st);
  for (std::size_t g = 0; g < md.m; ++g) pulled_back_conductance(md, st, scene_.material, g, &conductance_[6 * g]);
  classify_faces(md, st, dies, st.t);
  assemble(md, st, dies, 0.0, false, true, comm);
  st.thermal_dt = stable_step(md, comm);
  st.thermal_t = st.t, st.thermal_step = st.step;
}

void HeatTransfer::reproject(const Model& md, State& st, const Comm& comm) {
  if (md.tabled_heat()) {  // the enthalpy lumped: V_I e_I = sum_g w_g N_I(X_g) e(T_g)
    for (std::size_t g = 0; g < md.m; ++g) point_enthalpy_[g] = md.enthalpy(st.temperature[g]);
    const FixedScale scale = lump(md, &point_enthalpy_, &st.surface_heat, comm);
    for (std::size_t I = 0; I < md.n; ++I) st.particle_temperature[I] = md.temperature_of(scale.real(partial_[2 * I]) / capacity_[I]);
  } else {
    const FixedScale scale = lump(md, &st.temperature, &st.surface_heat, comm);
    for (std::size_t I = 0; I < md.n; ++I) st.particle_temperature[I] = scale.real(partial_[2 * I]) / capacity_[I];
  }
  settle(md, st);
}

// rho0 c sum_g w_g N_I(X_g) v_g (v = 1 without values; with a specific heat table without the rho0 c,
// v an enthalpy) plus the owned particles' `extra` (J) into partial_'s first slot, summed over the
// ranks; its scale.
FixedScale HeatTransfer::lump(const Model& md, const std::vector<double>* values, const std::vector<double>* extra,
                              const Comm& comm) {
  const double rho_c = md.tabled_heat() ? 1.0 : md.heat_capacity;
  auto v = [&](std::size_t g) { return values ? (*values)[g] : 1.0; };
  double most = 0;
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
      most = std::max(most, rho_c * md.weight[g] * std::abs(md.N[std::size_t(k)] * v(g)));
  for (std::size_t I = 0; extra && I < md.n; ++I) most = std::max(most, std::abs((*extra)[I]));
  comm.max(&most, 1);
  const FixedScale scale = FixedScale::for_bound(most, headroom_);
  std::fill(partial_.begin(), partial_.end(), Fixed(0));
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
      partial_[2 * std::size_t(md.nbr[k])] += scale.fixed(rho_c * md.weight[g] * md.N[std::size_t(k)] * v(g));
  for (std::size_t I = 0; extra && I < md.n; ++I)
    if (md.owned[I]) partial_[2 * I] += scale.fixed((*extra)[I]);
  exchange_->sum(partial_);
  return scale;
}

// The temperature faces' particles held, the points' T^h gathered, nothing pending.
void HeatTransfer::settle(const Model& md, State& st) {
  hold_faces(st);
  std::fill(st.heat_pending.begin(), st.heat_pending.end(), 0.0);
  std::fill(st.surface_heat.begin(), st.surface_heat.end(), 0.0);
  const std::vector<double>& field = field_values(md, st);
  for (std::size_t g = 0; g < md.m; ++g) st.temperature[g] = point_temperature(md, field, g);
}

const std::vector<double>& HeatTransfer::field_values(const Model& md, const State& st) {
  if (!md.tabled_heat()) return st.particle_temperature;
  for (std::size_t I = 0; I < md.n; ++I) enthalpy_[I] = md.enthalpy(st.particle_temperature[I]);
  return enthalpy_;
}

void HeatTransfer::hold_faces(State& st) const {
  for (std::size_t q = 0; q < fixed_particles_.size(); ++q) st.particle_temperature[fixed_particles_[q]] = fixed_temperature_[q];
}

bool HeatTransfer::due(const State& st, double dt) const {
  if (!(st.t > st.thermal_t)) return false;
  const int cap = scene_.thermal.max_steps_per_update;
  if (cap > 0 && st.step - st.thermal_step >= cap) return true;
  return st.t + dt - st.thermal_t > st.thermal_dt;
}

void HeatTransfer::update(const Model& md, State& st, DieContact& dies, const Comm& comm) {
  const double elapsed = st.t - st.thermal_t;
  const auto steps = std::max<std::int64_t>(1, std::int64_t(std::ceil(elapsed / st.thermal_dt)));
  const double dt = elapsed / double(steps);
  for (std::size_t g = 0; g < md.m; ++g) pulled_back_conductance(md, st, scene_.material, g, &conductance_[6 * g]);
  classify_faces(md, st, dies, st.t);
  for (std::int64_t s = 0; s < steps; ++s) {
    assemble(md, st, dies, dt, s == 0, s == 0, comm);
    if (md.tabled_heat())  // e_I += heat / V_I (enthalpy_ holds e(T_I) from the assembly)
      for (std::size_t I = 0; I < md.n; ++I) st.particle_temperature[I] = md.temperature_of(enthalpy_[I] + heat_[I] / capacity_[I]);
    else
      for (std::size_t I = 0; I < md.n; ++I) st.particle_temperature[I] += heat_[I] / capacity_[I];
    hold_faces(st);
    if (s + 1 < steps)  // the faces' temperatures for the next sub-step
      for (std::size_t f = 0; f < faces_.size(); ++f) faces_[f].T = face_temperature(md, st, f);
  }
  st.thermal_dt = stable_step(md, comm);
  settle(md, st);
  st.thermal_t = st.t, st.thermal_step = st.step;
  ++st.thermal_updates;
}

void HeatTransfer::classify_faces(const Model& md, const State& st, const DieContact& dies, double t) {
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    double centre[3];
    FaceState& face = faces_[f];
    face.area = surface_face(md, st, f, centre);
    face.T = face_temperature(md, st, f);
    face.die = dies.empty() ? -1 : dies.touching(centre, t, kFaceTouch * std::sqrt(face.area));
  }
}

void HeatTransfer::assemble(const Model& md, State& st, DieContact& dies, double dt, bool pending, bool bound,
                            const Comm& comm) {
  const bool tabled = md.tabled_heat();
  const Scene::Thermal& air = scene_.thermal;
  // the particles' field values: T_I, or with a specific heat table e_I = e(T_I), whose field's
  // gradient is grad e^h and its temperature's grad e^h / (rho0 c(T^h)); the conductance bounds are
  // then per unit of enthalpy (divided by rho0 c), against V_I in place of C_I
  const std::vector<double>& field = field_values(md, st);
  // the heat the point's pending rise stored (J)
  auto stored = [&](std::size_t g) {
    const double T = st.temperature[g], rise = st.heat_pending[g];
    return tabled ? md.weight[g] * (md.enthalpy(T) - md.enthalpy(T - rise)) : md.heat_capacity * md.weight[g] * rise;
  };
  // the points' fluxes w_g J_ref k J C^-1 grad T^h, and bounds on every contribution
  double most[2] = {0, 0};  // |heat| and |conductance| of one contribution
  for (std::size_t g = 0; g < md.m; ++g) {
    double grad[3] = {0, 0, 0}, odd[3] = {0, 0, 0}, sum_dN = grad_norm_sum_[g], e = 0, e_odd = 0;
    const std::int64_t k1 = md.nbr_offsets[g + 1];
    auto k = md.nbr_offsets[g];
    for (; k + 1 < k1; k += 2) {
      const double* d = &md.dN[3 * std::size_t(k)];
      const double v = field[std::size_t(md.nbr[k])], w = field[std::size_t(md.nbr[k + 1])];
      for (int i = 0; i < 3; ++i) grad[i] += d[i] * v, odd[i] += d[3 + i] * w;
      if (tabled) e += md.N[std::size_t(k)] * v, e_odd += md.N[std::size_t(k) + 1] * w;
    }
    if (k < k1) {
      const double* d = &md.dN[3 * std::size_t(k)];
      const double v = field[std::size_t(md.nbr[k])];
      for (int i = 0; i < 3; ++i) grad[i] += d[i] * v;
      if (tabled) e += md.N[std::size_t(k)] * v;
    }
    for (int i = 0; i < 3; ++i) grad[i] += odd[i];
    e += e_odd;
    if (tabled) {
      const double per_enthalpy = 1 / md.capacity_at(md.temperature_of(e));
      for (int i = 0; i < 3; ++i) grad[i] *= per_enthalpy;
      sum_dN *= per_enthalpy;
    }
    const double* K = &conductance_[6 * g];
    double* q = &flux_[3 * g];
    q[0] = K[0] * grad[0] + K[3] * grad[1] + K[5] * grad[2];
    q[1] = K[3] * grad[0] + K[1] * grad[1] + K[4] * grad[2];
    q[2] = K[5] * grad[0] + K[4] * grad[1] + K[2] * grad[2];
    const double q_norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    const double source = pending ? std::abs(stored(g)) * N_max_[g] : 0.0;
    most[0] = std::max(most[0], dt * q_norm * md.dN_max[g] + source);
    if (bound) {  // the conductance's Gershgorin bound, only where the stable step is refreshed
      spread_[g] = spectral_bound(K) * sum_dN;
      most[1] = std::max(most[1], spread_[g] * md.dN_max[g]);
    }
  }
  // the faces' heat flows into the part (W) and conductances (W/K), each shared by the face's nodes
  auto face_heat_flow = [&](const FaceState& f, double& conductance) {
    if (f.die >= 0) {
      const Die& die = scene_.dies[std::size_t(f.die)];
      conductance = die.heat_transfer * f.area;
      return f.area * contact_flux(die.heat_transfer, die.temperature, f.T);
    }
    if (f.die == -2) return conductance = 0, 0.0;
    conductance = f.area * (air.convection + radiation_conductance(air.emissivity, air.ambient_temperature, f.T));
    return f.area * (convection_flux(air.convection, air.ambient_temperature, f.T) +
                     radiation_flux(air.emissivity, air.ambient_temperature, f.T));
  };
  auto face_flow = [&](const FaceState& f, double& conductance) {
    const double flow = face_heat_flow(f, conductance);
    if (tabled) conductance /= md.capacity_at(f.T);
    return flow;
  };
  if (pending)  // the friction's heat at the particle slaves
    for (std::size_t I = 0; I < md.n; ++I) most[0] = std::max(most[0], std::abs(st.surface_heat[I]));
  for (const FaceState& f : faces_) {
    double c = 0;
    const double flow = face_flow(f, c);
    most[0] = std::max(most[0], dt * std::abs(flow) / 3);
    most[1] = std::max(most[1], c / 3);
  }
  comm.max(most, 2);
  const FixedScale heat = FixedScale::for_bound(most[0], headroom_), conductance = FixedScale::for_bound(most[1], headroom_);

  std::fill(partial_.begin(), partial_.end(), Fixed(0));
  for (std::size_t g = 0; g < md.m; ++g) {
    const double* q = &flux_[3 * g];
    const double heat_stored = pending ? stored(g) : 0.0;
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) {
      const double* d = &md.dN[3 * std::size_t(k)];
      Fixed* acc = &partial_[2 * std::size_t(md.nbr[k])];
      acc[0] += heat.fixed(md.N[std::size_t(k)] * heat_stored - dt * (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]));
      if (bound) acc[1] += conductance.fixed(spread_[g] * grad_norm_[std::size_t(k)]);
    }
  }
  if (pending)
    for (std::size_t I = 0; I < md.n; ++I) partial_[2 * I] += heat.fixed(st.surface_heat[I]);
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    double c = 0;
    const double flow = face_flow(faces_[f], c);
    const auto k0 = md.surface_face_offsets[f], k1 = md.surface_face_offsets[f + 1];
    const double share = 1.0 / double(k1 - k0);
    for (auto k = k0; k < k1; ++k) {
      Fixed* acc = &partial_[2 * std::size_t(md.surface_face_nodes[k])];
      acc[0] += heat.fixed(dt * flow * share);
      if (bound) acc[1] += conductance.fixed(c * share);
    }
    // the heat that left the part: into the die it touches, or to the ambient
    if (faces_[f].die >= 0) dies.totals()[std::size_t(faces_[f].die)].heat -= dt * flow;
    else st.ambient_heat -= dt * flow;
  }
  exchange_->sum(partial_);
  for (std::size_t I = 0; I < md.n; ++I) {
    heat_[I] = heat.real(partial_[2 * I]);
    if (bound) bound_[I] = conductance.real(partial_[2 * I + 1]);
  }
}

double HeatTransfer::stable_step(const Model& md, const Comm& comm) const {
  double dt = 1e300;
  for (std::size_t I = 0; I < md.n; ++I)
    if (bound_[I] > 0) dt = std::min(dt, 2 * kSafety * capacity_[I] / bound_[I]);
  comm.min(&dt, 1);
  return dt;
}

}  // namespace rk
