#include "io/output.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "error.hpp"
#include "h5file.hpp"
#include "io/durable_file.hpp"
#include "result_frame.hpp"
#include "rk/internal_force.hpp"
#include "material/damage.hpp"
#include "rk/kinematics.hpp"

namespace rk {
namespace {

// weight, eq_plastic_strain, von_mises, pressure, Cauchy stress (xx, yy, zz, xy, yz, zx); where the
// material has a temperature the temperature, the plastic strain rate and the flow stress; with damage
// its criteria
constexpr int kBase = 10, kThermal = 3, kDamage = int(kDamageCriteria), kProjected = kBase + kThermal + kDamage;
constexpr int kStress = 4;  // the first stress component's column


}  // namespace

double point_heat(const State& st, std::size_t g) {
  if (st.temperature.empty()) return 0.0;
  return st.particle_temperature.empty() ? st.temperature[g] : st.heat_pending[g];
}

double particle_field_temperature(const Model& md, const State& st, std::size_t I) {
  if (st.particle_temperature.empty()) return 0.0;
  double T = 0;  // with a specific heat table the shapes carry the enthalpy (thermal/heat_transfer.hpp)
  for (auto k = md.material_offsets[I]; k < md.material_offsets[I + 1]; ++k) {
    const double T_J = st.particle_temperature[std::size_t(md.material_cols[std::size_t(k)])];
    T += md.material_N[std::size_t(k)] * (md.tabled_heat() ? md.enthalpy(T_J) : T_J);
  }
  return md.tabled_heat() ? md.temperature_of(T) : T;
}

void cauchy_measures(const double* tau, double J, double& von_mises, double& pressure) {
  const double p = (tau[0] + tau[1] + tau[2]) / 3;
  const double s[6] = {tau[0] - p, tau[1] - p, tau[2] - p, tau[3], tau[4], tau[5]};
  const double q2 = 1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
  von_mises = std::sqrt(q2) / J;
  pressure = -p / J;
}

ResultWriter::ResultWriter(const std::string& case_dir, const Model& md, const std::string& scene_hash,
                           std::int64_t resume_frames)
    : case_dir_(case_dir), scene_hash_(scene_hash), thermal_col_(md.heat_capacity > 0 ? kBase : -1),
      damage_col_(md.damage_cockcroft_latham || md.damage_brozzo || md.damage_oyane ? kBase + (thermal_col_ > 0 ? kThermal : 0) : -1),
      projected_(kBase + (thermal_col_ > 0 ? kThermal : 0) + (damage_col_ > 0 ? kDamage : 0)),
      exchange_(md, projected_), partial_(std::size_t(projected_) * md.n) {
  const std::string dir = result_frame_dir(case_dir, md.rank);
  std::filesystem::create_directories(dir);
  frames_ = int(std::max<std::int64_t>(resume_frames, 0));
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {  // frames after the restart point
    const std::string file = entry.path().filename().string();
    const long long k = result_frame_number(file);
    if (k >= frames_ || (file.starts_with("frame_") && file.ends_with(".tmp"))) std::filesystem::remove(entry.path());
  }
}

void ResultWriter::write_frame(const Model& md, const State& st, const std::vector<double>& velocity,
                               const Comm& comm, const DieFrame& dies) {
  // Particle values of point quantities: the average q_I = sum_g a_gI q_g / sum_g a_gI over the points
  // whose supports hold the particle, a_gI = w_g max(N_I(X_g), 0): positive weights, so a particle's
  // value lies within its points' (a plastic strain is never negative, a von Mises stress never above
  // the points' flow stress; the RK values N_I themselves can be negative). Summed over ranks in fixed
  // point so every copy and every rank count gives the same value.
  const int np = projected_;
  std::vector<double> q(std::size_t(np) * md.m);
  double bound[kProjected] = {};
  for (std::size_t g = 0; g < md.m; ++g) {
    double vm, p;
    cauchy_measures(&st.tau[6 * g], st.total_J(g), vm, p);
    const double* tau = &st.tau[6 * g];
    const double J = st.total_J(g);
    const double rate = st.plastic_rate.empty() ? 0.0 : st.plastic_rate[g];
    double values[kProjected] = {1.0,        st.ep[g],   vm,         p,          tau[0] / J, tau[1] / J,
                                 tau[2] / J, tau[3] / J, tau[4] / J, tau[5] / J};
    if (thermal_col_ > 0) {
      values[thermal_col_] = point_heat(st, g), values[thermal_col_ + 1] = rate;
      values[thermal_col_ + 2] = md.material_at(g).law.flow_stress(st.ep[g], rate, st.temperature[g]);
    }
    for (int k = 0; damage_col_ > 0 && k < kDamage; ++k) values[damage_col_ + k] = st.damage[kDamageCriteria * g + std::size_t(k)];
    double nmax = 0;
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) nmax = std::max(nmax, std::abs(md.N[k]));
    for (int c = 0; c < np; ++c) {
      q[std::size_t(np) * g + c] = values[c];
      bound[c] = std::max(bound[c], md.weight[g] * nmax * std::abs(values[c]));
    }
  }
  comm.max(bound, np);
  FixedScale scale[kProjected];
  if (headroom_ < 0) headroom_ = force_headroom(md, 1, 0, comm);
  for (int c = 0; c < np; ++c) scale[c] = FixedScale::for_bound(bound[c], headroom_);
  std::fill(partial_.begin(), partial_.end(), Fixed(0));
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
      for (int c = 0; c < np; ++c)
        partial_[std::size_t(np) * std::size_t(md.nbr[k]) + c] +=
            scale[c].fixed(md.weight[g] * std::max(md.N[k], 0.0) * q[std::size_t(np) * g + c]);
  exchange_.sum(partial_);

  // Displacements: the material's, u^h(X_I) = sum_J N_J(X_I) d_J (RK coefficients are not values).
  std::vector<std::int64_t> gid;
  std::vector<double> x, u, v, ep, vm, pr, sigma, temperature, rate, flow;
  std::vector<double> damage[kDamageCriteria];
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    gid.push_back(md.global_id[I]);
    double uh[3] = {st.u[3 * I], st.u[3 * I + 1], st.u[3 * I + 2]};
    material_displacement(md, st, I, uh);
    for (int i = 0; i < 3; ++i) {
      x.push_back(md.X[3 * I + i] + uh[i]);
      u.push_back(uh[i]);
      v.push_back(velocity[3 * I + i]);
    }
    const double w = scale[0].real(partial_[std::size_t(np) * I]);
    auto value = [&](int c) { return w > 0 ? scale[c].real(partial_[std::size_t(np) * I + c]) / w : 0.0; };
    ep.push_back(value(1));
    vm.push_back(value(2));
    pr.push_back(value(3));
    for (int c = kStress; c < kStress + 6; ++c) sigma.push_back(value(c));
    if (thermal_col_ > 0) {  // with conduction T^h(X_I) and the pending heat, else the points' temperature
      temperature.push_back(particle_field_temperature(md, st, I) + value(thermal_col_));
      rate.push_back(value(thermal_col_ + 1)), flow.push_back(value(thermal_col_ + 2));
    }
    for (int k = 0; damage_col_ > 0 && k < kDamage; ++k) damage[k].push_back(value(damage_col_ + k));
  }
  const std::string path = result_frame_path(case_dir_, md.rank, frames_), tmp = path + ".tmp";
  try {
    H5File f(tmp, H5File::Mode::create);
    f.set_attr("format", kResultFrameFormat);
    f.set_attr("rank", std::int64_t(md.rank));
    f.set_attr("ranks", std::int64_t(md.ranks));
    f.set_attr("scene_hash", scene_hash_);
    const std::string g = result_frame_group(frames_);
    f.write(g + "time", std::vector<double>{st.t});
    f.write(g + "step", std::vector<std::int64_t>{st.step});
    f.write(g + "global_id", gid);
    f.write(g + "x", x, 3);
    if (!dies.stroke.empty()) {  // the dies (shared/result_frame.hpp)
      f.write(g + kDieStroke, dies.stroke);
      f.write(g + kDieLoad, dies.load, 4);
      f.write(g + kDieLoadScale, std::vector<double>{dies.load_scale});
      f.write(g + kDieTouched, dies.touched);
    }
    const std::vector<double>* fields[] = {&u, &v, &ep, &vm, &pr, &sigma};  // in kFrameFields' order
    static_assert(std::size(fields) == std::size(kFrameFields));
    for (std::size_t k = 0; k < std::size(fields); ++k)
      f.write(g + kFrameFields[k].name, *fields[k], std::size_t(kFrameFields[k].components));
    if (thermal_col_ > 0)
      for (const auto& [field, data] : {std::pair{kThermalFields[0], &temperature}, {kThermalFields[1], &rate}, {kThermalFields[2], &flow}})
        f.write(g + field.name, *data);
    for (std::size_t k = 0; damage_col_ > 0 && k < kDamageCriteria; ++k) f.write(g + kDamageFields[k].name, damage[k]);
    f.close();
  } catch (const Error&) {  // no partial frame is left behind
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
  commit_file(tmp, path);
  ++frames_;
}

}  // namespace rk
