#include "io/checkpoint.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "error.hpp"
#include "h5file.hpp"
#include "io/durable_file.hpp"
#include "material/damage.hpp"

namespace rk {

std::string checkpoint_path(const std::string& case_dir, int rank) {
  char name[40];
  std::snprintf(name, sizeof name, "/checkpoint/rank_%04d.h5", rank);
  return case_dir + name;
}

namespace {

constexpr std::size_t kClockScalars = 18;  // the run clock's doubles (write_temporary lists them)

std::vector<double> ram_rows(const State& st) {  // State::Ram's fields, a row per ram
  std::vector<double> rows;
  for (const State::Ram& r : st.rams)
    rows.insert(rows.end(), {r.stroke, r.speed, r.delivered, r.blows, r.stopped, r.since_t, r.since_s});
  return rows;
}

void write_temporary(const std::string& tmp, const Model& md, const State& st, const RunClock& c,
                     const DieContact& contact) {
  const std::vector<DieTotals>& dies = contact.totals();
  {
    H5File f(tmp, H5File::Mode::create);
    f.set_attr("rank", std::int64_t(md.rank));
    f.set_attr("particles", std::int64_t(md.n));
    f.set_attr("points", std::int64_t(md.m));
    f.set_attr("format", kCheckpointFormat);
    f.write("clock/scalars", std::vector<double>{st.t, st.dt_half, c.max_error, st.external_work, c.next_output,
                                                 c.next_history, c.dt_stable, c.kinetic0, c.last_error, c.max_ke_ratio,
                                                 st.update_work, st.viscous_work, c.max_pressure_ratio, st.thermal_work, c.dt_penalty,
                                                 c.max_ke_ratio_late, st.part_contact_work, c.energy_scale});
    f.write("clock/integers", std::vector<std::int64_t>{st.step, c.frames, std::int64_t(dies.size())});
    std::vector<double> die_work;
    for (const auto& d : dies) die_work.insert(die_work.end(), {d.press_work, d.friction_work, d.contact_work});
    f.write("dies/work", die_work, 3);
    if (!st.rams.empty()) f.write("dies/rams", ram_rows(st), State::kRamValues);
    if (!contact.touched().empty()) f.write("dies/touched", contact.touched());
    f.write("dies/sticks", contact.stick_rows(), DieContact::kStickValues);
    f.set_attr("reference_updates", st.reference_updates);
    f.write("particles/global_id", md.global_id);
    f.write("particles/u", st.u, 3);
    f.write("particles/v", st.v, 3);
    f.write("points/cp_inv", st.cp_inv, 6);
    f.write("points/ep", st.ep);
    f.write("points/wp", st.wp);
    if (!st.q.empty()) {  // bulk viscosity: q and det F at the last step
      f.write("points/q", st.q);
      f.write("points/J_last", st.J_last);
    }
    if (!st.temperature.empty()) f.write("points/temperature", st.temperature);
    if (!st.particle_dt_half.empty()) f.write("particles/dt_half", st.particle_dt_half), f.write("cells/t_last", st.cell_t_last);
    if (!st.stiff_mode.empty()) {  // time.stable_step = frequency
      f.write("particles/stiff_mode", st.stiff_mode, 3);
      f.write("clock/step_ratio", std::vector<double>{st.step_ratio});
    }
    if (!st.stretch_last.empty()) {  // a thermal strain: its work over the next step takes the stress before it
      f.write("points/stretch_last", st.stretch_last);
      f.write("points/tau", st.tau, 6);
    }
    if (!st.damage.empty()) f.write("points/damage", st.damage, kDamageCriteria);
    if (!st.plastic_rate.empty()) f.write("points/plastic_rate", st.plastic_rate);
    if (!st.particle_temperature.empty()) {  // conduction (thermal/heat_transfer.hpp)
      f.write("particles/temperature", st.particle_temperature);
      f.write("particles/surface_heat", st.surface_heat);
      f.write("points/heat_pending", st.heat_pending);
      f.write("thermal/scalars", std::vector<double>{st.thermal_t, st.thermal_dt, st.ambient_heat});
      f.write("thermal/integers", std::vector<std::int64_t>{st.thermal_step, st.thermal_updates});
      std::vector<double> die_heat;
      for (const auto& d : dies) die_heat.push_back(d.heat);
      f.write("thermal/die_heat", die_heat);
    }
    if (st.reference_updates > 0) {  // the reference configuration (rk/reference_update.hpp)
      f.write("particles/u_ref", st.u_ref, 3);
      f.write("points/X", md.point_X, 3);
      f.write("points/J_ref", st.J_ref);
    }
    f.close();
  }
  // The new checkpoint must read back, every dataset equal to what was written, before it replaces
  // the last good one (on a full file system a dataset can come back unallocated).
  bool readable = false;
  try {
    H5File check(tmp, H5File::Mode::read);
    readable = check.read<double>("clock/scalars").size() == kClockScalars && check.read<std::int64_t>("clock/integers").size() == 3 &&
               check.read<double>("dies/work", 3).size() == 3 * dies.size() && check.read<double>("particles/u", 3) == st.u &&
               check.read<double>("particles/v", 3) == st.v && check.read<double>("points/cp_inv", 6) == st.cp_inv &&
               check.read<double>("points/ep") == st.ep && check.read<double>("points/wp") == st.wp &&
               (st.q.empty() || (check.read<double>("points/q") == st.q && check.read<double>("points/J_last") == st.J_last)) &&
               (st.rams.empty() || check.read<double>("dies/rams", State::kRamValues) == ram_rows(st)) &&
               (contact.touched().empty() || check.read<std::int64_t>("dies/touched") == contact.touched()) &&
               check.read<double>("dies/sticks", DieContact::kStickValues) == contact.stick_rows() &&
               (st.temperature.empty() || check.read<double>("points/temperature") == st.temperature) &&
               (st.particle_dt_half.empty() || (check.read<double>("particles/dt_half") == st.particle_dt_half &&
                                                check.read<double>("cells/t_last") == st.cell_t_last)) &&
               (st.stiff_mode.empty() || (check.read<double>("particles/stiff_mode", 3) == st.stiff_mode &&
                                          check.read<double>("clock/step_ratio") == std::vector<double>{st.step_ratio})) &&
               (st.stretch_last.empty() || (check.read<double>("points/stretch_last") == st.stretch_last &&
                                            check.read<double>("points/tau", 6) == st.tau)) &&
               (st.damage.empty() || check.read<double>("points/damage", kDamageCriteria) == st.damage) &&
               (st.plastic_rate.empty() || check.read<double>("points/plastic_rate") == st.plastic_rate) &&
               (st.particle_temperature.empty() || (check.read<double>("particles/temperature") == st.particle_temperature &&
                                                    check.read<double>("points/heat_pending") == st.heat_pending &&
                                                    check.read<double>("particles/surface_heat") == st.surface_heat &&
                                                    check.read<double>("thermal/die_heat").size() == dies.size())) &&
               (st.reference_updates == 0 ||
                (check.read<double>("particles/u_ref", 3) == st.u_ref && check.read<double>("points/X", 3) == md.point_X &&
                 check.read<double>("points/J_ref") == st.J_ref));
  } catch (const Error&) {
  }
  if (!readable) throw Error(tmp + ": the checkpoint did not read back (disk full?); the previous one is kept");
}

}  // namespace

void write_checkpoint(const std::string& case_dir, const Model& md, const State& st, const RunClock& c,
                      const DieContact& dies) {
  const std::string path = checkpoint_path(case_dir, md.rank), tmp = path + ".tmp";
  std::filesystem::create_directories(case_dir + "/checkpoint");
  try {
    write_temporary(tmp, md, st, c, dies);
  } catch (const Error&) {  // leave no partial file behind; the last good checkpoint stays
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
  // the last good one becomes the previous (a kill between the renames leaves the previous and
  // the complete temporary file: the restart falls back to the previous on every rank)
  if (std::filesystem::exists(path) && std::rename(path.c_str(), (path + ".previous").c_str()) != 0)
    throw Error(path + ": cannot keep the previous checkpoint (rename failed)");
  commit_file(tmp, path);  // fsync, rename, fsync the folder
}

void remove_checkpoints(const std::string& case_dir, int rank) {
  const std::string path = checkpoint_path(case_dir, rank);
  for (const std::string& p : {path, path + ".previous"}) {
    std::error_code failed;
    std::filesystem::remove(p, failed);
    if (failed) throw Error(p + ": an earlier run's checkpoint cannot be removed (" + failed.message() + ")");
  }
}

namespace {

std::int64_t checkpoint_step(const std::string& path) {  // -1: absent or unreadable
  if (!std::filesystem::exists(path)) return -1;
  try {
    const auto i = H5File(path, H5File::Mode::read).read<std::int64_t>("clock/integers");
    return i.size() == 3 ? i[0] : -1;
  } catch (const Error&) {
    return -1;
  }
}

}  // namespace

std::string restart_checkpoint(const std::string& case_dir, const Comm& comm) {
  const std::string newest = checkpoint_path(case_dir, comm.rank()), previous = newest + ".previous";
  const std::int64_t mine[2] = {checkpoint_step(newest), checkpoint_step(previous)};
  double step = double(std::max(mine[0], mine[1]));
  // (the lowest rank without any names its file)
  comm.check(step >= 0, case_dir + "/checkpoint: no complete checkpoint of every rank to restart from: " + newest +
                            " and its .previous are missing or unreadable (run without --restart)");
  comm.min(&step, 1);
  const bool held = mine[0] == std::int64_t(step) || mine[1] == std::int64_t(step);
  comm.check(held, newest + ": this rank holds no checkpoint of step " + std::to_string(std::int64_t(step)) +
                       ", the newest every other rank holds (run without --restart)");
  return mine[0] == std::int64_t(step) ? newest : previous;
}

void read_checkpoint(const std::string& path, Model& md, State& st, RunClock& c, DieContact& contact,
                     const DieCarry* stage) {
  std::vector<DieTotals>& dies = contact.totals();
  H5File f(path, H5File::Mode::read);
  const std::int64_t updates = f.exists("particles/global_id") ? f.attr_int("reference_updates") : 0;
  if ((updates == 0 && f.attr_int("particles") != std::int64_t(md.n)) || f.attr_int("points") != std::int64_t(md.m))
    throw Error(path + ": the checkpoint does not match this case's subdomain (re-run from the start)");
  // a rank's checkpoint read by another (swapped or copied files of equal sizes passed the counts above, and the
  // restart ran on the wrong particles and overwrote the finished run's last frame)
  if (f.has_attr("rank") && f.attr_int("rank") != std::int64_t(md.rank))
    throw Error(path + ": the checkpoint of rank " + std::to_string(f.attr_int("rank")) + ", here read by rank " +
                std::to_string(md.rank) + " (its files swapped, or copied from another run?)");
  if (!f.has_attr("format") || f.attr_int("format") != kCheckpointFormat)
    throw Error(path + ": a checkpoint of another rksolve version (format " +
                (f.has_attr("format") ? std::to_string(f.attr_int("format")) : std::string("1")) + ", this one reads " +
                std::to_string(kCheckpointFormat) + "); re-run from the start");
  const auto s = f.read<double>("clock/scalars");
  const auto i = f.read<std::int64_t>("clock/integers");
  // the totals are the dies', then the rigid walls' and symmetry planes' (the same in every stage)
  const std::size_t own = contact.size(), held = dies.size() - own, before = stage ? stage->previous_triangles.size() : own;
  const std::size_t written_dies = before + held;
  if (s.size() != kClockScalars || i.size() != 3 || i[2] != std::int64_t(written_dies))
    throw Error(path + ": the checkpoint's run clock or die count does not match");
  // this case's die k is the checkpoint's die written[k] (-1: none)
  std::vector<int> written(dies.size());
  for (std::size_t k = 0; k < dies.size(); ++k)
    written[k] = k >= own ? int(before + k - own) : stage ? stage->continues[k] : int(k);
  st.t = s[0], st.dt_half = s[1], c.max_error = s[2], st.external_work = s[3];
  c.next_output = s[4], c.next_history = s[5], c.dt_stable = s[6], c.kinetic0 = s[7], c.last_error = s[8],
  c.max_ke_ratio = s[9], st.update_work = s[10], st.viscous_work = s[11];
  c.max_pressure_ratio = s[12], st.thermal_work = s[13], c.dt_penalty = s[14];
  c.max_ke_ratio_late = s[15], st.part_contact_work = s[16], c.energy_scale = s[17];
  st.step = i[0], c.frames = i[1];
  const auto work = f.read<double>("dies/work", 3);
  for (std::size_t k = 0; k < dies.size(); ++k)
    if (const int j = written[k]; j >= 0)
      dies[k].press_work = work[3 * j], dies[k].friction_work = work[3 * j + 1], dies[k].contact_work = work[3 * j + 2];
  if (stage)  // a die the stage leaves out: the work it did on the part stays in the balance
    for (std::size_t j = 0; j < before; ++j)
      if (std::find(written.begin(), written.end(), int(j)) == written.end()) st.external_work += work[3 * j + 2];
  if (!contact.touched().empty() && !stage) {
    if (!f.exists("dies/touched")) throw Error(path + ": the checkpoint holds no die fill; re-run from the start");
    const auto touched = f.read<std::int64_t>("dies/touched");
    if (touched.size() != contact.touched().size()) throw Error(path + ": the checkpoint's die surfaces do not match this case's");
    contact.touched() = touched;
  } else if (!contact.touched().empty() && f.exists("dies/touched")) {  // a stage: the continuing dies' fill
    const auto touched = f.read<std::int64_t>("dies/touched");
    std::vector<std::size_t> first(before + 1, 0);
    for (std::size_t j = 0; j < before; ++j) first[j + 1] = first[j] + stage->previous_triangles[j];
    if (touched.size() != first.back()) throw Error(path + ": the checkpoint's die surfaces do not match its case's");
    for (std::size_t k = 0; k < own; ++k)
      if (const int j = written[k]; j >= 0)
        std::copy(touched.begin() + std::ptrdiff_t(first[std::size_t(j)]), touched.begin() + std::ptrdiff_t(first[std::size_t(j) + 1]),
                  contact.touched().begin() + std::ptrdiff_t(contact.triangle0(k)));
  }
  {  // Coulomb friction's sticks; in a stage, those on the dies that continue, renumbered as this stage's
    const std::size_t cols = DieContact::kStickValues;
    std::vector<double> rows = f.read<double>("dies/sticks", cols), kept;
    for (std::size_t r = 0; r + cols <= rows.size(); r += cols) {
      const bool face = rows[r + 1] < 0;  // a boundary face's, its die as -(j + 1)
      const int j = int(face ? -rows[r + 1] - 1 : rows[r + 1]);
      const auto k = std::find(written.begin(), written.begin() + std::ptrdiff_t(own), j) - written.begin();
      if (std::size_t(k) == own) continue;  // its die does not continue
      rows[r + 1] = face ? -double(k + 1) : double(k);
      kept.insert(kept.end(), rows.begin() + std::ptrdiff_t(r), rows.begin() + std::ptrdiff_t(r + cols));
    }
    contact.set_stick_rows(kept, path);
  }
  if (f.exists("dies/rams") && !stage) {  // the rams of the dies driven by their press
    const auto rows = f.read<double>("dies/rams", State::kRamValues);
    st.rams.resize(rows.size() / State::kRamValues);
    for (std::size_t r = 0; r < st.rams.size(); ++r) {
      const double* v = &rows[State::kRamValues * r];
      st.rams[r] = {v[0], v[1], v[2], v[3], v[4], v[5], v[6]};
    }
  }
  st.cp_inv = f.read<double>("points/cp_inv", 6);
  st.ep = f.read<double>("points/ep");
  st.wp = f.read<double>("points/wp");
  if (st.ep.size() != md.m) throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
  if (!st.q.empty()) {  // bulk viscosity on: its state must be there (written by a run with it on)
    if (!f.exists("points/q"))
      throw Error(path + ": the checkpoint was written with bulk_viscosity off; restart with the same settings");
    st.q = f.read<double>("points/q");
    st.J_last = f.read<double>("points/J_last");
    if (st.q.size() != md.m || st.J_last.size() != md.m)
      throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
  }
  if (!st.temperature.empty()) {  // a Johnson-Cook material: its temperatures must be there
    if (!f.exists("points/temperature"))
      throw Error(path + ": the checkpoint holds no temperatures (written with another material); restart with the same scene");
    st.temperature = f.read<double>("points/temperature");
    if (st.temperature.size() != md.m) throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
  }
  if (!st.stretch_last.empty()) {  // a thermal strain
    if (!f.exists("points/stretch_last"))
      throw Error(path + ": the checkpoint holds no thermal stretches (written without a thermal strain); restart with the same scene");
    st.stretch_last = f.read<double>("points/stretch_last");
    if (!f.exists("points/tau"))
      throw Error(path + ": the checkpoint holds no stresses for the thermal strain's work (an older rksolve); re-run from the start");
    st.tau = f.read<double>("points/tau", 6);
    if (st.stretch_last.size() != md.m || st.tau.size() != 6 * md.m)
      throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
  }
  if (!st.damage.empty()) {
    if (!f.exists("points/damage"))
      throw Error(path + ": the checkpoint holds no damage (written without a 'damage' section); restart with the same scene");
    st.damage = f.read<double>("points/damage", kDamageCriteria);
    if (st.damage.size() != kDamageCriteria * md.m) throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
  }
  if (!st.plastic_rate.empty()) {  // shear friction's flow stress takes the rate
    if (!f.exists("points/plastic_rate"))
      throw Error(path + ": the checkpoint holds no plastic strain rates (written without a die's shear_factor); "
                         "restart with the same scene");
    st.plastic_rate = f.read<double>("points/plastic_rate");
    if (st.plastic_rate.size() != md.m) throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
  }
  std::vector<double> T, friction;  // the particles' temperature coefficients and friction heat (conduction)
  if (!st.particle_temperature.empty()) {
    if (!f.exists("thermal"))
      throw Error(path + ": the checkpoint holds no heat conduction state (written without material.conductivity); "
                         "restart with the same scene");
    T = f.read<double>("particles/temperature");
    friction = f.read<double>("particles/surface_heat");
    st.heat_pending = f.read<double>("points/heat_pending");
    const auto ts = f.read<double>("thermal/scalars");
    const auto ti = f.read<std::int64_t>("thermal/integers");
    const auto die_heat = f.read<double>("thermal/die_heat");
    if (st.heat_pending.size() != md.m || ts.size() != 3 || ti.size() != 2 || die_heat.size() != written_dies)
      throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
    st.thermal_t = ts[0], st.thermal_dt = ts[1], st.ambient_heat = ts[2];
    st.thermal_step = ti[0], st.thermal_updates = ti[1];
    for (std::size_t k = 0; k < dies.size(); ++k)
      if (const int j = written[k]; j >= 0) dies[k].heat = die_heat[std::size_t(j)];
  }
  const auto u = f.read<double>("particles/u", 3), v = f.read<double>("particles/v", 3);
  // time.stable_step = frequency: the power iteration's vector and ratio (a stage, or a checkpoint
  // without them, starts them afresh)
  std::vector<double> mode;
  if (!st.stiff_mode.empty() && !stage && f.exists("particles/stiff_mode")) {
    mode = f.read<double>("particles/stiff_mode", 3);
    st.step_ratio = f.read<double>("clock/step_ratio").at(0);
    if (mode.size() != u.size()) throw Error(path + ": checkpoint datasets disagree with each other's counts");
  } else {
    st.stiff_mode.clear();
  }
  // multi-rate steps: each particle's last step and each cell's last update (a checkpoint without them,
  // or a stage's: every particle's the global step, every cell updated now)
  std::vector<double> dt_half;  // (the checkpoint's local particles)
  if (!st.particle_dt_half.empty()) {
    std::fill(st.particle_dt_half.begin(), st.particle_dt_half.end(), st.dt_half);
    std::fill(st.cell_t_last.begin(), st.cell_t_last.end(), st.t);
    if (f.exists("particles/dt_half") && !stage) {
      dt_half = f.read<double>("particles/dt_half");
      st.cell_t_last = f.read<double>("cells/t_last");
      if (dt_half.size() != u.size() / 3 || st.cell_t_last.size() != md.cells)
        throw Error(path + ": checkpoint datasets disagree with each other's counts");
    }
  }
  if (updates == 0) {
    st.u = u, st.v = v;
    if (!dt_half.empty()) st.particle_dt_half = dt_half;
    if (!mode.empty()) st.stiff_mode = mode;
    if (!T.empty()) st.particle_temperature = T, st.surface_heat = friction;
    if (st.u.size() != 3 * md.n || st.v.size() != 3 * md.n || (!T.empty() && (T.size() != md.n || friction.size() != md.n)))
      throw Error(path + ": checkpoint datasets disagree with the subdomain's counts");
    return;
  }
  // Written after reference updates: its local particles are not the subdomain's. The owned ones
  // (always in both) are taken by global id; the caller rebuilds on the checkpoint's reference.
  const auto gid = f.read<std::int64_t>("particles/global_id");
  const auto u_ref = f.read<double>("particles/u_ref", 3);
  md.point_X = f.read<double>("points/X", 3);
  st.J_ref = f.read<double>("points/J_ref");
  if (u.size() != 3 * gid.size() || v.size() != u.size() || u_ref.size() != u.size() || md.point_X.size() != 3 * md.m ||
      st.J_ref.size() != md.m || (!T.empty() && (T.size() != gid.size() || friction.size() != gid.size())))
    throw Error(path + ": checkpoint datasets disagree with each other's counts");
  st.u_ref.assign(3 * md.n, 0.0);
  std::size_t k = 0;
  for (std::size_t I = 0; I < md.n; ++I) {
    while (k < gid.size() && gid[k] < md.global_id[I]) ++k;
    const bool found = k < gid.size() && gid[k] == md.global_id[I];
    if (!found && md.owned[I])
      throw Error(path + ": owned particle " + std::to_string(md.global_id[I]) + " is missing from the checkpoint");
    if (found) {
      for (int i = 0; i < 3; ++i) st.u[3 * I + i] = u[3 * k + i], st.v[3 * I + i] = v[3 * k + i], st.u_ref[3 * I + i] = u_ref[3 * k + i];
      if (!dt_half.empty()) st.particle_dt_half[I] = dt_half[k];
      if (!T.empty()) st.particle_temperature[I] = T[k], st.surface_heat[I] = friction[k];
      if (!mode.empty())
        for (int i = 0; i < 3; ++i) st.stiff_mode[3 * I + i] = mode[3 * k + i];
    }
  }
  st.reference_updates = updates;
}

}  // namespace rk
