#include "contact/part_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_laws.hpp"
#include "rk/kinematics.hpp"
#include "rk/surface_faces.hpp"

namespace rk {
namespace {

constexpr double kApart = 1.0;    // of one body: more than this many spacings apart at t = 0
constexpr double kFacing = -0.5;  // n_I . n_J below this: the normals more than 120 degrees apart
// d = kDiameter h (h: discretization.spacing): a particle of a square lattice's gaps is 0.71 h from its
// corners, of a triangular one's 0.58 h, so a sphere of 0.75 h blocks both with room for the springs'
// depth. One distance for every pair: two flat faces meet at once, not pair by pair as the particles'
// own spacings would have them (a bar's end face of an O-grid mesh spans 0.68-0.87 h)
constexpr double kDiameter = 0.75;

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

PartContact::PartContact(const Model& md, const Scene& scene, const Comm& comm)
    : on_(scene.part_contact()), self_(scene.contact.self), penalty_scale_(scene.penalty_scale_at_cfl()),
      d_(kDiameter * scene.discretization.spacing) {
  if (!on_) return;
  // the free faces: not on a symmetry plane (within 1e-9 of the coordinates' scale, their round-off)
  const std::size_t faces = md.surface_face_offsets.size() - 1;
  for (std::size_t f = 0; f < faces; ++f) {
    bool on_plane = false;
    for (const SymmetryPlane& p : scene.symmetry_planes) {
      bool all = true;
      for (auto k = md.surface_face_offsets[f]; k < md.surface_face_offsets[f + 1]; ++k) {
        const double* X = &md.Xr[3 * std::size_t(md.surface_face_nodes[std::size_t(k)])];
        const double gap = (X[0] - p.point[0]) * p.normal[0] + (X[1] - p.point[1]) * p.normal[1] + (X[2] - p.point[2]) * p.normal[2];
        all = all && std::abs(gap) <= 1e-9 * (std::abs(X[0]) + std::abs(X[1]) + std::abs(X[2]) + d_);
      }
      on_plane = on_plane || all;
    }
    if (!on_plane) free_faces_.push_back(std::int32_t(f));
  }
  std::vector<Fixed> count(md.n, 0);  // each particle's free faces over all ranks
  for (auto f : free_faces_)
    for (auto k = md.surface_face_offsets[std::size_t(f)]; k < md.surface_face_offsets[std::size_t(f) + 1]; ++k)
      ++count[std::size_t(md.surface_face_nodes[std::size_t(k)])];
  OverlapExchange(md, 1).sum(count);
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I] && count[I] > 0) slaves_.push_back(std::int32_t(I));
  N_max_.assign(slaves_.size(), 0.0);
  for (std::size_t s = 0; s < slaves_.size(); ++s) {
    const auto I = std::size_t(slaves_[s]);
    for (auto k = md.material_offsets[I]; k < md.material_offsets[I + 1]; ++k)
      N_max_[s] = std::max(N_max_[s], std::abs(md.material_N[std::size_t(k)]));
  }
  normal_sum_.assign(3 * md.n, 0);
  normal_exchange_ = std::make_unique<OverlapExchange>(md, 3);
  mine_.resize(kRecord * slaves_.size());
  boxes_.resize(6 * std::size_t(comm.size()));
  send_counts_.resize(std::size_t(comm.size()));
  active_.reserve(slaves_.size());
}

// Each particle's free faces' unit outward normals now, summed over the ranks (a face is on one rank).
void PartContact::normals(const Model& md, const State& st) {
  std::fill(normal_sum_.begin(), normal_sum_.end(), Fixed(0));
  const double scale = std::ldexp(1.0, 48);  // unit components: 2^14 faces at a particle before int64 overflows
  for (auto f : free_faces_) {
    double centre[3], a[3];
    const double area = surface_face(md, st, std::size_t(f), centre, a);
    if (!(area > 0)) continue;
    for (auto k = md.surface_face_offsets[std::size_t(f)]; k < md.surface_face_offsets[std::size_t(f) + 1]; ++k)
      for (int i = 0; i < 3; ++i)
        normal_sum_[3 * std::size_t(md.surface_face_nodes[std::size_t(k)]) + i] += Fixed(a[i] / area * scale);
  }
  normal_exchange_->sum(normal_sum_);
}

// Each slave's record: its global id, material point, outward normal, place at t = 0, spacing, mass, body.
void PartContact::pack(const Model& md, const State& st) {
  normals(md, st);
  for (std::size_t s = 0; s < slaves_.size(); ++s) {
    const auto I = std::size_t(slaves_[s]);
    double* r = &mine_[kRecord * s];
    r[0] = double(md.global_id[I]);
    material_position(md, st, I, r + 1);
    double n[3], length = 0;
    for (int i = 0; i < 3; ++i) n[i] = double(normal_sum_[3 * I + i]), length += n[i] * n[i];
    length = std::sqrt(length);
    for (int i = 0; i < 3; ++i) r[4 + i] = length > 0 ? n[i] / length : 0.0;
    for (int i = 0; i < 3; ++i) r[7 + i] = md.X[3 * I + i];
    r[10] = md.spacing0[I], r[11] = md.mass[I], r[12] = double(md.body[I]);
  }
}

// candidates_: this rank's slaves, then the other ranks' surface particles that may reach them.
void PartContact::exchange(const Comm& comm) {
  candidates_.assign(mine_.begin(), mine_.end());
  if (comm.size() == 1) return;
  double box[6] = {kInf, kInf, kInf, -kInf, -kInf, -kInf};
  for (std::size_t s = 0; s < slaves_.size(); ++s)
    for (int i = 0; i < 3; ++i) box[i] = std::min(box[i], mine_[kRecord * s + 1 + i]), box[3 + i] = std::max(box[3 + i], mine_[kRecord * s + 1 + i]);
  comm.all_gather(box, 6, boxes_.data());
  send_.clear();
  for (int q = 0; q < comm.size(); ++q) {
    const double* b = &boxes_[6 * std::size_t(q)];
    const std::size_t before = send_.size();
    if (q != comm.rank())
      for (std::size_t s = 0; s < slaves_.size(); ++s) {
        const double* x = &mine_[kRecord * s + 1];
        bool inside = true;
        for (int i = 0; i < 3; ++i) inside = inside && x[i] >= b[i] - d_ && x[i] <= b[3 + i] + d_;
        if (inside) send_.insert(send_.end(), &mine_[kRecord * s], &mine_[kRecord * (s + 1)]);
      }
    send_counts_[std::size_t(q)] = int(send_.size() - before);
  }
  comm.exchange(send_, send_counts_, received_, recv_counts_);
  candidates_.insert(candidates_.end(), received_.begin(), received_.end());
}

// The candidates sorted by their bin (cubes of side d over their box): a pair closer than d lies in
// neighbouring bins. A sorted list rather than a grid: its size follows the surface, not the box.
void PartContact::bin() {
  const std::size_t n = candidates_.size() / kRecord;
  double hi[3] = {-kInf, -kInf, -kInf};
  for (int i = 0; i < 3; ++i) lo_[i] = kInf;
  for (std::size_t c = 0; c < n; ++c)
    for (int i = 0; i < 3; ++i)
      lo_[i] = std::min(lo_[i], candidates_[kRecord * c + 1 + i]), hi[i] = std::max(hi[i], candidates_[kRecord * c + 1 + i]);
  for (int i = 0; i < 3; ++i) dims_[i] = n > 0 ? std::floor((hi[i] - lo_[i]) / d_) + 1 : 1;
  bins_.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    const double* x = &candidates_[kRecord * c + 1];
    bins_[c] = {key(x), std::int32_t(c)};
  }
  std::sort(bins_.begin(), bins_.end());
}

std::int64_t PartContact::key(const double x[3], int dx, int dy, int dz) const {
  const int d[3] = {dx, dy, dz};
  std::int64_t b[3];
  for (int i = 0; i < 3; ++i) {
    b[i] = std::int64_t(std::floor((x[i] - lo_[i]) / d_)) + d[i];
    if (b[i] < 0 || b[i] >= std::int64_t(dims_[i])) return -1;
  }
  return b[0] + std::int64_t(dims_[0]) * (b[1] + std::int64_t(dims_[1]) * b[2]);
}

// Slave s's pairs, summed in the order of the partners' ids; returns its spring energy share.
double PartContact::pair_force(std::size_t s, double dt, double dt_min, double f[3]) {
  const double* a = &mine_[kRecord * s];
  hits_.clear();
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const std::int64_t k = key(a + 1, dx, dy, dz);
        if (k < 0) continue;
        auto it = std::lower_bound(bins_.begin(), bins_.end(), std::make_pair(k, std::numeric_limits<std::int32_t>::min()));
        for (; it != bins_.end() && it->first == k; ++it) {
          const double* b = &candidates_[kRecord * std::size_t(it->second)];
          if (b[0] == a[0]) continue;  // itself
          double e[3], r2 = 0;
          for (int i = 0; i < 3; ++i) e[i] = a[1 + i] - b[1 + i], r2 += e[i] * e[i];
          const double d = d_, r = std::sqrt(r2);
          if (!(r < d) || !(r > 0)) continue;
          // in front of each other's surfaces, the normals facing
          if (!(dot3(e, b + 4) > 0) || !(dot3(e, a + 4) < 0) || !(dot3(a + 4, b + 4) < kFacing)) continue;
          if (a[12] == b[12]) {  // one body: only what was apart at t = 0, and only with self-contact on
            double X2 = 0;
            for (int i = 0; i < 3; ++i) X2 += (a[7 + i] - b[7 + i]) * (a[7 + i] - b[7 + i]);
            const double apart = kApart * std::max(a[10], b[10]);
            if (!self_ || X2 <= apart * apart) continue;
          }
          const double k_IJ = penalty_stiffness(penalty_scale_, a[11] * b[11] / (a[11] + b[11]), dt_min, dt);
          Hit h{b[0], {}, 0.25 * k_IJ * (d - r) * (d - r), d - r};
          for (int i = 0; i < 3; ++i) h.f[i] = k_IJ * (d - r) * e[i] / r;
          hits_.push_back(h);
        }
      }
  std::sort(hits_.begin(), hits_.end(), [](const Hit& x, const Hit& y) { return x.id < y.id; });
  f[0] = f[1] = f[2] = 0;
  double energy = 0;
  for (const Hit& h : hits_) {
    for (int i = 0; i < 3; ++i) f[i] += h.f[i];
    energy += h.energy;
    max_penetration_ = std::max(max_penetration_, h.depth);
  }
  return energy;
}

double PartContact::compute(const Model& md, const State& st, double dt, double dt_min, const Comm& comm) {
  active_.clear();
  spring_energy_ = max_penetration_ = 0;
  if (!on_) return 0;
  pack(md, st);
  exchange(comm);
  bin();
  double largest = 0;
  for (std::size_t s = 0; s < slaves_.size(); ++s) {
    Active a{std::int32_t(s), {}};
    const double energy = pair_force(s, dt, dt_min, a.f);
    if (hits_.empty()) continue;
    spring_energy_ += energy;
    for (int i = 0; i < 3; ++i) largest = std::max(largest, N_max_[s] * std::abs(a.f[i]));
    active_.push_back(a);
  }
  return largest;
}

void PartContact::add_to(const Model& md, std::vector<Fixed>& partial, const FixedScale& scale) const {
  for (const Active& a : active_) {  // f acts on the field at the slave: N_J f on d_J
    const auto I = std::size_t(slaves_[std::size_t(a.slave)]);
    for (auto k = md.material_offsets[I]; k < md.material_offsets[I + 1]; ++k)
      for (int i = 0; i < 3; ++i)
        partial[kForceStride * std::size_t(md.material_cols[std::size_t(k)]) + i] -= scale.fixed(md.material_N[std::size_t(k)] * a.f[i]);
  }
}

void PartContact::account(const Model& md, State& st, const std::vector<double>& v_old, double dt_avg) const {
  for (const Active& a : active_) {
    const auto I = std::size_t(slaves_[std::size_t(a.slave)]);
    double before[3], after[3];
    material_velocity(md, v_old, I, before);
    material_velocity(md, st.v, I, after);
    for (int i = 0; i < 3; ++i) st.part_contact_work += dt_avg * a.f[i] * 0.5 * (before[i] + after[i]);
  }
}

void PartContact::count_terms(const Model& md, std::vector<Fixed>& terms) const {
  for (const auto I : slaves_)
    for (auto k = md.material_offsets[std::size_t(I)]; k < md.material_offsets[std::size_t(I) + 1]; ++k)
      ++terms[std::size_t(md.material_cols[std::size_t(k)])];
}

}  // namespace rk
