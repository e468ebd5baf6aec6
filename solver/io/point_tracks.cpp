#include "io/point_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/output.hpp"
#include "material/damage.hpp"
#include "rk/kinematics.hpp"

namespace rk {
namespace {

constexpr int kTemperature = 6;  // a track's temperature column: after x, y, z, eq_plastic_strain, von_mises, pressure

}  // namespace

PointTracks::PointTracks(const std::string& case_dir, const Scene& scene, const Model& md, double resume_time,
                         const Comm& comm) {
  const auto& tracks = scene.output.track;
  if (tracks.empty()) return;
  const bool thermal = scene.material.thermal(), damage = scene.damage.on();
  values_ = 6 + (thermal ? 1 : 0) + (damage ? int(kDamageCriteria) : 0);
  for (const auto& t : tracks) {
    // the nearest owned particle at t = 0, then the lowest global id among the equally near
    double best = std::numeric_limits<double>::infinity(), id = best, spacing = 0;
    for (std::size_t I = 0; I < md.n; ++I) {
      if (!md.owned[I]) continue;
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (md.X[3 * I + i] - t.point[i]) * (md.X[3 * I + i] - t.point[i]);
      if (d2 < best || (d2 == best && double(md.global_id[I]) < id)) best = d2, id = double(md.global_id[I]), spacing = md.spacing0[I];
    }
    double nearest = best;
    comm.min(&nearest, 1);
    double chosen = best == nearest ? id : std::numeric_limits<double>::infinity();
    comm.min(&chosen, 1);
    double h = best == nearest && id == chosen ? spacing : 0;  // the chosen particle's spacing
    comm.max(&h, 1);
    comm.check(std::sqrt(nearest) <= h, "output.track '" + t.name + "': no particle within a spacing of its point (" +
                                               std::to_string(t.point[0]) + ", " + std::to_string(t.point[1]) + ", " +
                                               std::to_string(t.point[2]) + ") m: outside the part?");
    ids_.push_back(chosen);
  }
  sums_.assign(tracks.size() * std::size_t(values_ + 2), 0.0);
  row_.assign(1 + tracks.size() * std::size_t(values_), 0.0);
  std::vector<std::string> columns{"time"};
  for (const auto& t : tracks) {
    for (const char* q : {".x", ".y", ".z", ".eq_plastic_strain", ".von_mises", ".pressure"}) columns.push_back(t.name + q);
    if (thermal) columns.push_back(t.name + ".temperature");
    if (damage)
      for (const auto& q : kDamageFields) columns.push_back(t.name + "." + q.name);
  }
  writer_ = collectively(comm, [&] {
    return comm.rank() == 0 ? std::make_unique<HistoryWriter>(case_dir + "/tracks.csv", columns, resume_time) : nullptr;
  });
}

// The tracked particles held here and the points whose supports hold them, in the order of the
// points and their neighbours (the sums' order, so the rows do not depend on this list).
void PointTracks::map_locals(const Model& md, std::int64_t updates) {
  std::vector<int> track_of(md.n, -1);
  owned_.clear(), terms_.clear();
  for (std::size_t I = 0; I < md.n; ++I)
    for (std::size_t t = 0; t < ids_.size(); ++t)
      if (double(md.global_id[I]) == ids_[t]) {
        track_of[I] = int(t);
        if (md.owned[I]) owned_.push_back({I, int(t)});
      }
  for (std::size_t g = 0; g < md.m; ++g)
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k)
      if (const int t = track_of[std::size_t(md.nbr[k])]; t >= 0) terms_.push_back({g, std::size_t(k), t});
  mapped_ = {updates, md.m, md.nbr.size()};
}

void PointTracks::record(const Model& md, const State& st, const Comm& comm) {
  if (ids_.empty()) return;
  // the local numbering and the supports change at a reference update only
  if (mapped_ != Mapping{st.reference_updates, md.m, md.nbr.size()}) map_locals(md, st.reference_updates);
  // the positive weights' sum, the values, then the particle's own T^h (the owner's, with conduction)
  const std::size_t stride = std::size_t(values_) + 2;
  std::fill(sums_.begin(), sums_.end(), 0.0);
  for (const auto& [I, t] : owned_) {  // the position, and with conduction T^h there, from the owner
    double x[3];
    material_position(md, st, I, x);
    double* s = &sums_[stride * std::size_t(t)];
    for (int i = 0; i < 3; ++i) s[1 + i] = x[i];
    s[stride - 1] = particle_field_temperature(md, st, I);
  }
  for (const Term& q : terms_) {  // every point once, on its rank
    const std::size_t g = q.point;
    const double a = md.weight[g] * std::max(md.N[q.neighbour], 0.0);
    double vm, p;
    cauchy_measures(&st.tau[6 * g], st.total_J(g), vm, p);
    double* s = &sums_[stride * std::size_t(q.track)];
    s[0] += a;
    s[4] += a * st.ep[g], s[5] += a * vm, s[6] += a * p;
    int c = 7;
    if (!st.temperature.empty()) s[c++] += a * point_heat(st, g);
    for (std::size_t k = 0; k < kDamageCriteria && !st.damage.empty(); ++k) s[c++] += a * st.damage[kDamageCriteria * g + k];
  }
  comm.sum(sums_.data(), int(sums_.size()));
  row_[0] = st.t;
  for (std::size_t t = 0; t < ids_.size(); ++t) {
    const double* s = &sums_[stride * t];
    double* r = &row_[1 + std::size_t(values_) * t];
    for (int i = 0; i < 3; ++i) r[i] = s[1 + i];
    for (int c = 3; c < values_; ++c) r[c] = s[0] > 0 ? s[1 + c] / s[0] : 0.0;
    if (!st.temperature.empty()) r[kTemperature] += s[stride - 1];  // (the frames': T^h and the pending heat)
  }
  collectively(comm, [&] { return writer_ ? (writer_->write(row_), 0) : 0; });  // a full disk stops all ranks
}

}  // namespace rk
