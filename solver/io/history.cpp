#include "io/history.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "error.hpp"
#include "history_columns.hpp"
#include "material/damage.hpp"

namespace rk {
namespace {

// HistorySums' fields in the order they travel in the row's reduction.
constexpr double HistorySums::* kSumFields[] = {
    &HistorySums::contacts,     &HistorySums::point_contacts, &HistorySums::spring_energy,
    &HistorySums::friction_work, &HistorySums::contact_work,  &HistorySums::volume,
    &HistorySums::ebc_work,     &HistorySums::update_work,    &HistorySums::viscous_work,
    &HistorySums::heat,         &HistorySums::ambient_heat,   &HistorySums::part_contacts};
constexpr std::size_t kSumCount = std::size(kSumFields);
constexpr std::size_t kPerDie = 5;  // fx, fy, fz, press work, heat

}  // namespace

HistoryWriter::HistoryWriter(const std::string& path, const std::vector<std::string>& columns, double resume_time) {
  std::vector<std::string> keep;
  if (resume_time >= 0) {  // rows before the checkpoint survive a restart
    std::ifstream in(path);
    std::string line, header;
    for (std::size_t k = 0; k < columns.size(); ++k) header += (k ? "," : "") + columns[k];
    if (std::getline(in, line) && line != header)  // rows of another layout would land under the wrong names
      throw Error(path + ": written with other columns (\"" + line.substr(0, 80) +
                  "...\"); move it away to restart into a new history");
    // a row's time is printed to 10 digits: the row at the checkpoint's own time can read up to 5e-10
    // of it below, and the restart writes that row again
    while (std::getline(in, line))
      if (std::strtod(line.c_str(), nullptr) < resume_time * (1 - 1e-9)) keep.push_back(line);
  }
  path_ = path;
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw Error(path + ": cannot write the history file");
  for (std::size_t k = 0; k < columns.size(); ++k) std::fprintf(file_, "%s%s", k ? "," : "", columns[k].c_str());
  std::fprintf(file_, "\n");
  for (const auto& line : keep) std::fprintf(file_, "%s\n", line.c_str());
  if (std::fflush(file_) != 0 || std::ferror(file_)) {
    std::fclose(file_);
    throw Error(path + ": write failed (disk full?)");
  }
}

HistoryWriter::~HistoryWriter() {
  if (file_) std::fclose(file_);
}

void HistoryWriter::write(const std::vector<double>& values) {
  for (std::size_t k = 0; k < values.size(); ++k) std::fprintf(file_, "%s%.10g", k ? "," : "", values[k]);
  std::fprintf(file_, "\n");
  if (std::fflush(file_) != 0 || std::ferror(file_)) throw Error(path_ + ": write failed (disk full?)");
}

History::History(const std::string& case_dir, const Scene& scene, const Model& md, double resume_time, const Comm& comm)
    : scene_(scene), columns_(history_columns(scene)), row_(columns_.size(), 0.0) {
  writer_ = collectively(comm, [&] {
    return comm.rank() == 0 ? std::make_unique<HistoryWriter>(case_dir + "/history.csv", columns_, resume_time)
                            : std::unique_ptr<HistoryWriter>();
  });
  for (std::size_t g = 0; g < md.m; ++g) volume0_ += md.weight[g];
  comm.sum(&volume0_, 1);
  const std::size_t faces = scene.fixed_faces.size() + scene.prescribed_faces.size();
  sums_.resize(kSumCount + scene.rigid_walls.size() + kPerDie * scene.dies.size() + 3 * faces);
}

HistoryRow History::record(const Model& md, const State& st, const DieContact& dies, const PartContact& parts,
                           const std::vector<double>& filled,
                           const EssentialBcs& ebc,
                           const std::vector<double>& v_old, double dt, double kinetic0, double& energy_scale,
                           const Comm& comm) {
  HistoryRow out;
  Energies& e = out.energies;
  e = compute_energies(md, st, v_old, comm);
  // this rank's shares: the scalars, then one force per rigid wall, (fx, fy, fz, press work) per die,
  // then (fx, fy, fz) per fixed or prescribed face
  HistorySums s;
  s.ebc_work = ebc.step_work();
  s.update_work = st.update_work;
  s.viscous_work = st.viscous_work;
  s.ambient_heat = st.ambient_heat;
  for (std::size_t g = 0; g < md.m; ++g) s.volume += md.weight[g] * st.total_J(g);
  double coolest = 1e300, hottest = -1e300;  // empty without a temperature
  for (std::size_t g = 0; g < st.temperature.size(); ++g) {
    s.heat += md.weight[g] * st.temperature[g];
    coolest = std::min(coolest, st.temperature[g]), hottest = std::max(hottest, st.temperature[g]);
  }
  const std::size_t walls = scene_.rigid_walls.size(), die0 = kSumCount + walls, face0 = die0 + kPerDie * dies.size();
  std::fill(sums_.begin(), sums_.end(), 0.0);
  for (std::size_t w = 0; w < walls; ++w) sums_[kSumCount + w] = dies.wall_force(w);
  double penetration = 0;
  for (std::size_t d = 0; d < dies.totals().size(); ++d) {  // the dies, the rigid walls, then the symmetry planes
    const DieTotals& t = dies.totals()[d];
    s.spring_energy += t.spring_energy, s.friction_work += t.friction_work, s.contact_work += t.contact_work;
    if (d >= dies.size() + walls) continue;
    s.contacts += double(t.contacts);
    s.point_contacts += double(t.point_contacts);
    penetration = std::max(penetration, t.max_penetration);
    if (d >= dies.size()) continue;
    double* die = &sums_[die0 + kPerDie * d];
    die[0] = t.force[0], die[1] = t.force[1], die[2] = t.force[2], die[3] = t.press_work, die[4] = t.heat;
  }
  const double tools_depth = penetration;  // the dies' and walls' alone (the parts' own contact below)
  s.contact_work += st.part_contact_work, s.spring_energy += parts.spring_energy();
  s.part_contacts = double(parts.contacts());
  penetration = std::max(penetration, parts.max_penetration());
  std::copy(ebc.reactions().begin(), ebc.reactions().end(), sums_.begin() + std::ptrdiff_t(face0));
  for (std::size_t k = 0; k < kSumCount; ++k) sums_[k] = s.*kSumFields[k];
  comm.sum(sums_.data(), int(sums_.size()));
  for (std::size_t k = 0; k < kSumCount; ++k) s.*kSumFields[k] = sums_[k];
  // then the damage criteria's largest values (0 without damage)
  double worst[6 + kDamageCriteria] = {penetration, ebc.max_error(md, st, st.t), dies.symmetry_depth(), -coolest, hottest};
  worst[5 + kDamageCriteria] = tools_depth;
  for (std::size_t k = 0; k < st.damage.size(); ++k) worst[5 + k % kDamageCriteria] = std::max(worst[5 + k % kDamageCriteria], st.damage[k]);
  comm.max(worst, int(std::size(worst)));
  out.ebc_error = worst[1];
  out.penetration = worst[5 + kDamageCriteria];

  // The balance of the part (docs/scene.md, "Energy"): KE + internal = KE0 + W_ext + W_contact, with
  // W_contact the work of the contact forces on the material they hold. The penalty springs' energy
  // k d^2 / 2 is part of that work already (the dies' work less the springs' and friction's share),
  // so it is not counted again; it is reported in its own column.
  e.contact = s.contact_work;
  e.external -= 0.5 * s.ebc_work;
  Energies balance = e;  // the kinetic energy reference updates smoothed away is not an error
  balance.external += s.update_work;
  out.energy_error = energy_error(balance, kinetic0, energy_scale);
  out.kinetic_internal = e.internal > 0 ? e.kinetic / e.internal : 0.0;

  std::size_t c = 0;
  for (double v : {st.t, dt, e.kinetic, e.internal, e.plastic, e.external, e.contact, out.energy_error, s.friction_work,
                   s.contacts, s.point_contacts, worst[0], out.kinetic_internal, s.volume / volume0_ - 1, worst[1],
                   s.update_work, s.spring_energy, worst[2], s.viscous_work})
    row_[c++] = v;
  if (!st.temperature.empty())
    for (double v : {s.heat / volume0_, -worst[3], worst[4]}) row_[c++] = v;
  const bool conducting = !st.particle_temperature.empty();
  if (conducting) row_[c++] = s.ambient_heat;
  for (std::size_t k = 0; k < kDamageCriteria && !st.damage.empty(); ++k) row_[c++] = worst[5 + k];
  if (scene_.part_contact()) row_[c++] = s.part_contacts;
  for (std::size_t w = 0; w < walls; ++w) row_[c++] = sums_[kSumCount + w];
  std::size_t ram = 0;  // the press-driven dies' rams, in die order
  for (std::size_t d = 0; d < dies.size(); ++d) {
    const Die& die = dies.die(d);
    const double* f = &sums_[die0 + kPerDie * d];
    row_[c++] = dies.stroke(d, st.t);
    row_[c++] = die.force_factor * (f[0] * die.motion.direction[0] + f[1] * die.motion.direction[1] +
                                    f[2] * die.motion.direction[2]);
    row_[c++] = f[0], row_[c++] = f[1], row_[c++] = f[2];
    row_[c++] = f[3];
    row_[c++] = filled[d];
    if (conducting) row_[c++] = f[4];
    if (die.motion.driven()) row_[c++] = dies.rate(d, st.t), row_[c++] = st.rams[ram++].delivered;  // vbar over the step
  }
  const std::size_t fixed = scene_.fixed_faces.size();
  for (std::size_t f = 0; f < fixed + scene_.prescribed_faces.size(); ++f) {
    if (f >= fixed) row_[c++] = scene_.prescribed_faces[f - fixed].motion.stroke(st.t);
    for (int i = 0; i < 3; ++i) row_[c++] = sums_[face0 + 3 * f + i];
  }
  collectively(comm, [&] { return writer_ ? (writer_->write(row_), 0) : 0; });  // a full disk stops all ranks
  return out;
}

}  // namespace rk
