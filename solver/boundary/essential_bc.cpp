#include "boundary/essential_bc.hpp"

#include <algorithm>
#include <cmath>

#include "boundary/constraints.hpp"
#include "checked_int.hpp"
#include "error.hpp"
#include "rk/kinematics.hpp"

namespace rk {
namespace {

// One owned constrained particle as gathered: global id, directions, row N_J(X_I) by global id.
struct Record {
  std::int64_t gid = 0;
  std::vector<double> e;  // 3 per direction
  std::vector<std::int64_t> cols;
  std::vector<double> N, inv_mass;
};

std::vector<double> pack(const Model& md) {
  std::vector<double> out;
  for (std::size_t q = 0; q < md.ebc_particles.size(); ++q) {
    const auto I = md.ebc_particles[q];
    const auto k0 = md.constraint_offsets[I], k1 = md.constraint_offsets[I + 1];
    out.push_back(double(md.global_id[I]));
    out.push_back(double(k1 - k0));
    out.insert(out.end(), &md.constraint_dirs[3 * k0], &md.constraint_dirs[3 * k1]);
    out.push_back(double(md.ebc_offsets[q + 1] - md.ebc_offsets[q]));
    for (auto k = md.ebc_offsets[q]; k < md.ebc_offsets[q + 1]; ++k) {
      const auto J = md.ebc_cols[k];
      out.insert(out.end(), {double(md.global_id[J]), md.ebc_N[k], 1.0 / md.mass[J]});
    }
  }
  return out;
}

std::vector<Record> unpack(const std::vector<double>& all) {
  std::vector<Record> recs;
  for (std::size_t i = 0; i < all.size();) {
    Record r;
    r.gid = std::int64_t(all[i++]);
    const auto dirs = std::size_t(all[i++]);
    r.e.assign(&all[i], &all[i] + 3 * dirs);
    i += 3 * dirs;
    const auto nnz = std::size_t(all[i++]);
    for (std::size_t k = 0; k < nnz; ++k, i += 3) {
      r.cols.push_back(std::int64_t(all[i]));
      r.N.push_back(all[i + 1]);
      r.inv_mass.push_back(all[i + 2]);
    }
    recs.push_back(std::move(r));
  }
  std::sort(recs.begin(), recs.end(), [](const Record& a, const Record& b) { return a.gid < b.gid; });
  return recs;
}

std::int32_t local_index(const Model& md, std::int64_t gid) {  // -1: not on this rank
  auto it = std::lower_bound(md.global_id.begin(), md.global_id.end(), gid);
  return it != md.global_id.end() && *it == gid ? std::int32_t(it - md.global_id.begin()) : -1;
}

}  // namespace

EssentialBcs::EssentialBcs(const Model& md, const Scene& scene, const Comm& comm) : comm_(comm) {
  for (const auto& f : scene.prescribed_faces) motions_.push_back(f.motion);
  reaction_.assign(3 * reported_faces(scene), 0.0);
  std::vector<double> held = md.face_particles;
  held.push_back(0);
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I]) held.back() += md.constraint_offsets[I + 1] - md.constraint_offsets[I];
  comm.sum(held.data(), int(held.size()));
  rows_ = std::int64_t(held.back());
  for (std::size_t f = 0; f < all_faces(scene); ++f)
    comm.check(held[f] > 0,
               face_label(scene, f) + ": no particle of the part lies on this plane; check its point and normal");
  if (scene.discretization.ebc_method != "transformation" || rows_ == 0) return;

  // The whole constraint system on every rank, in global-id order: the same on any rank count.
  const std::vector<Record> recs = unpack(comm.gather_all(pack(md)));
  std::vector<std::int64_t> colg;
  for (const auto& r : recs) colg.insert(colg.end(), r.cols.begin(), r.cols.end());
  std::sort(colg.begin(), colg.end());
  colg.erase(std::unique(colg.begin(), colg.end()), colg.end());
  ConstraintRows A;
  A.cols = 3 * std::int64_t(colg.size());
  particle_rows_.assign(1, 0);
  for (const auto& r : recs) {
    for (std::size_t k = 0; k < r.e.size() / 3; ++k) {
      const double* e = &r.e[3 * k];
      dirs_.insert(dirs_.end(), e, e + 3);
      for (std::size_t j = 0; j < r.cols.size(); ++j) {
        const auto c = std::lower_bound(colg.begin(), colg.end(), r.cols[j]) - colg.begin();
        for (int d = 0; d < 3; ++d)
          if (e[d] != 0) A.col.push_back(3 * c + d), A.val.push_back(r.N[j] * e[d] * std::sqrt(r.inv_mass[j]));
      }
      A.offsets.push_back(std::int64_t(A.col.size()));
    }
    particle_rows_.push_back(std::int32_t(dirs_.size() / 3));
  }
  A.rows = std::int64_t(dirs_.size() / 3);
  factor_ = std::make_unique<ConstraintFactor>(A);

  for (auto I : md.ebc_particles) {
    const auto p = std::lower_bound(recs.begin(), recs.end(), md.global_id[I],
                                    [](const Record& r, std::int64_t g) { return r.gid < g; }) - recs.begin();
    own_first_row_.push_back(particle_rows_[p]);
  }
  std::vector<std::vector<std::pair<std::int32_t, double>>> fix(md.n);  // per local particle: (p, N)
  for (std::size_t p = 0; p < recs.size(); ++p)
    for (std::size_t j = 0; j < recs[p].cols.size(); ++j) {
      const auto J = local_index(md, recs[p].cols[j]);
      if (J >= 0) fix[J].emplace_back(std::int32_t(p), recs[p].N[j]);
    }
  fix_offsets_.assign(1, 0);
  for (const auto& list : fix) {
    for (const auto& [p, N] : list) fix_particle_.push_back(p), fix_N_.push_back(N);
    fix_offsets_.push_back(std::int32_t(fix_N_.size()));
  }
  checked_int(std::int64_t(fix_N_.size()), "rank " + std::to_string(md.rank) + ": the constraint rows' entries on local particles");
  rho_.resize(std::size_t(rows_));
  lambda_.resize(std::size_t(rows_));
  w_.resize(3 * recs.size());
}

double EssentialBcs::value(const Model& md, std::int32_t k, double t, bool rate) const {
  const auto f = md.constraint_value_face[k];
  if (f < 0) return 0.0;
  return md.constraint_coef[k] * (rate ? motions_[f].rate(t) : motions_[f].stroke(t));
}

void EssentialBcs::apply(const Model& md, State& st, double t_next, double dt, double dt_avg,
                         const std::vector<double>& v_old) {
  std::fill(reaction_.begin(), reaction_.end(), 0.0);
  const double work0 = st.external_work;
  if (exact()) apply_exact(md, st, t_next, dt, dt_avg, v_old);
  else apply_nodal(md, st, t_next, dt, dt_avg, v_old);
  step_work_ = st.external_work - work0;
}

void EssentialBcs::apply_nodal(const Model& md, State& st, double t_next, double dt, double dt_avg,
                               const std::vector<double>& v_old) {
  // the work summed in a register, in the same order (through st it is a load and a store a term, each
  // waiting on the last: v's stores may alias it)
  double work = st.external_work;
  for (std::size_t I = 0; I < md.n; ++I) {
    const auto k0 = md.constraint_offsets[I], k1 = md.constraint_offsets[I + 1];
    if (k0 == k1) continue;
    double* v = &st.v[3 * I];
    const double* u = &st.u[3 * I];
    const double before[3] = {v[0], v[1], v[2]};
    for (auto k = k0; k < k1; ++k) {
      const double* e = &md.constraint_dirs[3 * k];
      const double target = dt > 0 ? (value(md, k, t_next, false) - (e[0] * u[0] + e[1] * u[1] + e[2] * u[2])) / dt
                                   : value(md, k, t_next, true);
      const double delta = target - (e[0] * v[0] + e[1] * v[1] + e[2] * v[2]);
      for (int i = 0; i < 3; ++i) v[i] += delta * e[i];
      const auto f = md.constraint_face[k];
      if (dt > 0 && md.owned[I] && f >= 0)
        for (int i = 0; i < 3; ++i) reaction_[3 * f + i] += md.mass[I] * delta * e[i] / dt_avg;
    }
    if (dt > 0 && md.owned[I])
      for (int i = 0; i < 3; ++i) work += md.mass[I] * (v[i] - before[i]) * 0.5 * (v_old[3 * I + i] + v[i]);
  }
  st.external_work = work;
}

void EssentialBcs::apply_exact(const Model& md, State& st, double t_next, double dt, double dt_avg,
                               const std::vector<double>& v_old) {
  std::fill(rho_.begin(), rho_.end(), 0.0);
  for (std::size_t q = 0; q < md.ebc_particles.size(); ++q) {  // residuals of the owned rows
    const auto I = md.ebc_particles[q];
    for (auto k = md.constraint_offsets[I]; k < md.constraint_offsets[I + 1]; ++k) {
      const double* e = &md.constraint_dirs[3 * k];
      double Cv = 0, Cu = 0;
      for (auto j = md.ebc_offsets[q]; j < md.ebc_offsets[q + 1]; ++j) {
        const auto J = md.ebc_cols[j];
        const double* v = &st.v[3 * J];
        const double* u = &st.u[3 * J];
        Cv += md.ebc_N[j] * (e[0] * v[0] + e[1] * v[1] + e[2] * v[2]);
        Cu += md.ebc_N[j] * (e[0] * u[0] + e[1] * u[1] + e[2] * u[2]);
      }
      const double target = dt > 0 ? (value(md, k, t_next, false) - Cu) / dt : value(md, k, t_next, true);
      rho_[own_first_row_[q] + (k - md.constraint_offsets[I])] = Cv - target;
    }
  }
  comm_.sum(rho_.data(), int(rho_.size()));  // one owner per row: the sum is exact
  factor_->solve(rho_.data(), lambda_.data());
  for (std::size_t p = 0; p + 1 < particle_rows_.size(); ++p) {  // w_p = sum_k e_k lambda_k
    double* w = &w_[3 * p];
    w[0] = w[1] = w[2] = 0;
    for (auto a = particle_rows_[p]; a < particle_rows_[p + 1]; ++a)
      for (int i = 0; i < 3; ++i) w[i] += dirs_[3 * a + i] * lambda_[a];
  }
  for (std::size_t J = 0; J < md.n; ++J) {  // v_J -= M_J^{-1} sum_p N_J(X_p) w_p
    if (fix_offsets_[J] == fix_offsets_[J + 1]) continue;
    double dv[3] = {0, 0, 0};
    for (auto k = fix_offsets_[J]; k < fix_offsets_[J + 1]; ++k)
      for (int i = 0; i < 3; ++i) dv[i] -= fix_N_[k] * w_[3 * fix_particle_[k] + i];
    double* v = &st.v[3 * J];
    for (int i = 0; i < 3; ++i) v[i] += dv[i] / md.mass[J];
    if (dt > 0 && md.owned[J])
      for (int i = 0; i < 3; ++i) st.external_work += dv[i] * 0.5 * (v_old[3 * J + i] + v[i]);
  }
  if (dt > 0)  // each row's impulse on the part is -lambda e (the row's N_J sum to one)
    for (std::size_t q = 0; q < md.ebc_particles.size(); ++q) {
      const auto I = md.ebc_particles[q];
      for (auto k = md.constraint_offsets[I]; k < md.constraint_offsets[I + 1]; ++k) {
        const auto f = md.constraint_face[k];
        const double lambda = lambda_[own_first_row_[q] + (k - md.constraint_offsets[I])];
        if (f >= 0)
          for (int i = 0; i < 3; ++i) reaction_[3 * f + i] -= lambda * md.constraint_dirs[3 * k + i] / dt_avg;
      }
    }
}

void EssentialBcs::project(const Model& md, std::size_t I, double t, double* x) const {
  for (auto k = md.constraint_offsets[I]; k < md.constraint_offsets[I + 1]; ++k) {  // orthonormal e_k
    const double* e = &md.constraint_dirs[3 * k];
    double miss = -value(md, k, t, false);
    for (int i = 0; i < 3; ++i) miss += e[i] * (x[i] - md.X[3 * I + i]);
    for (int i = 0; i < 3; ++i) x[i] -= miss * e[i];
  }
}

double EssentialBcs::max_error(const Model& md, const State& st, double t) const {
  double worst = 0;
  for (std::size_t q = 0; q < md.ebc_particles.size(); ++q) {
    const auto I = md.ebc_particles[q];
    double uh[3];
    constrained_displacement(md, st, q, uh);
    for (auto k = md.constraint_offsets[I]; k < md.constraint_offsets[I + 1]; ++k) {
      const double* e = &md.constraint_dirs[3 * k];
      const double Cu = e[0] * uh[0] + e[1] * uh[1] + e[2] * uh[2];
      worst = std::max(worst, std::abs(Cu - value(md, k, t, false)));
    }
  }
  return worst;
}

}  // namespace rk
