#include "io/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "material/damage.hpp"
#include "process_memory.hpp"
#include "rk/kinematics.hpp"

namespace rk {

namespace {

// of the smallest spacing: a soft contact past it (the test suite's runs at the default penalty go in up to
// 0.075 of their median spacing, the Taylor bar's impact on a penalty wall; the back extrusion 0.037)
constexpr double kSoftContactDepth = 0.2;
// of the energy scale: reference updates that took more (the Taylor bar at reference_updates.strain 0.2, the
// updates as designed, gives 6.3 %; at 1e-6, 13-14 %)
constexpr double kLostToUpdates = 0.1;

// Collective; the summary is complete on rank 0.
RunSummary summarize(const Scene& scene, const Model& md, const State& st, const RunClock& clock, const DieContact& dies,
                     const EssentialBcs& ebc, const PhaseTimer& timer, const RunCounts& counts, const Comm& comm) {
  const double wall = comm.wtime() - counts.wall0;
  double owned = 0;
  for (std::size_t I = 0; I < md.n; ++I) owned += md.owned[I];
  double sums[6] = {owned, double(md.m), double(md.nbr.size()), counts.plastic_updates, counts.point_updates,
                    st.viscous_work};
  comm.sum(sums, 6);
  const double particles = sums[0], points = sums[1], neighbours = sums[2], plastic = sums[3], updates = sums[4];
  std::array<double, kPhaseCount> lo = timer.seconds, hi = timer.seconds;
  comm.min(lo.data(), kPhaseCount);
  comm.max(hi.data(), kPhaseCount);
  // memory: the largest rank's peak, and per integration point (with its share of the particles,
  // neighbours and shape functions) the data above the program's own baseline, summed over ranks:
  // at the peak (setup temporaries included) and resident at the end (what the time loop holds)
  const double peak_mb = process_memory_mb("VmHWM:");
  double mem_max = peak_mb, mem_sum[2] = {peak_mb - counts.baseline_mb, process_memory_mb("VmRSS:") - counts.baseline_mb};
  comm.max(&mem_max, 1);
  comm.sum(mem_sum, 2);
  const double bytes_per_mb_point = 1048576.0 / std::max(points, 1.0);
  // Suspicious but legal: a die that never touched the part (another unit, a wrong place, a motion
  // away from the part) leaves a run with no forming in it. Its work and heat over the run
  // (checkpointed) are 0.
  std::vector<double> touched(dies.size());
  for (std::size_t d = 0; d < dies.size(); ++d) {
    const DieTotals& t = dies.totals()[d];
    touched[d] = std::abs(t.press_work) + std::abs(t.contact_work) + std::abs(t.friction_work) + std::abs(t.heat);
  }
  comm.sum(touched.data(), int(touched.size()));
  RunSummary s;
  for (std::size_t d = 0; d < dies.size(); ++d)
    if (touched[d] == 0)
      s.warnings.push_back("die '" + scene.dies[d].name + "' never touched the part in this run: check its CAD unit (dies[" +
                           std::to_string(d) + "].unit), its position and its motion's direction");
  // A crack predicted: a damage criterion at or above the scene's critical value, where it is largest
  const std::pair<const char*, double> criteria[kDamageCriteria] = {
      {"cockcroft_latham", scene.damage.cockcroft_latham_critical}, {"brozzo", scene.damage.brozzo_critical},
      {"oyane", scene.damage.oyane_critical}};
  for (std::size_t k = 0; k < kDamageCriteria && !st.damage.empty(); ++k) {
    double most = 0, at[4] = {0, 0, 0, 0};  // the largest value; the position(s) holding it, and their count
    std::size_t where = 0;
    for (std::size_t g = 0; g < md.m; ++g)
      if (st.damage[kDamageCriteria * g + k] > most) most = st.damage[kDamageCriteria * g + k], where = g;
    double largest = most;
    comm.max(&largest, 1);
    if (most == largest && largest > 0) point_position(md, st, where, at), at[3] = 1;
    comm.sum(at, 4);
    const double critical = criteria[k].second;
    if (critical > 0 && largest >= critical) {
      char text[300];
      std::snprintf(text, sizeof text,
                    "crack predicted: damage %s reached %.4g (critical %.4g, damage.%s.critical) at (%.4g, %.4g, %.4g) m; "
                    "the frames' field damage_%s shows where",
                    criteria[k].first, largest, critical, criteria[k].first, at[0] / at[3], at[1] / at[3], at[2] / at[3],
                    criteria[k].first);
      s.warnings.push_back(text);
    }
  }
  // Mass scaling that changed the answer: a quasi-static forming run keeps its kinetic energy a
  // small part of the internal energy (under 5 %, the usual bound for explicit forming codes) once
  // the start-up transient has passed (judged over the run's second half: early on the internal
  // energy is small and the ratio large in any run); more means inertia carries part of the load.
  // Only where something drives the part: a part nothing moves (still dies, no moving faces, gravity or
  // initial velocity) has no forming for inertia to disturb, and its energies are a thermal strain's
  // micro-joules, whose ratio means nothing (a billet cooling on a still die read 5e4 %).
  const Vec3& g = scene.loads.gravity;
  const bool driven = counts.v_start > 0 || g[0] != 0 || g[1] != 0 || g[2] != 0;
  if (driven && md.mass_scaling > 1 && clock.max_ke_ratio_late > kMaxQuasiStaticKineticRatio) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "mass scaling (density x %.3g to reach time.mass_scaling_dt = %.3g s) let the kinetic energy reach "
                  "%.3g %% of the internal energy in the second half of the run (a quasi-static run stays under "
                  "%.3g %%): inertia is changing the forces; lower time.mass_scaling_dt or slow the dies",
                  md.mass_scaling, scene.time.mass_scaling_dt, 100 * clock.max_ke_ratio_late, 100 * kMaxQuasiStaticKineticRatio);
    s.warnings.push_back(text);
  }
  // A soft contact: the penalty lets the material into the tools by a fair part of a spacing (a run at
  // contact.penalty_scale 1e-9 let the die into the upsetting's billet by 0.22 of its smallest spacing in
  // 0.5 ms, and on through it): the tools' forces read low
  if (counts.h_min > 0 && counts.max_penetration > kSoftContactDepth * counts.h_min) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "the material went %.3g m (%.2g of the particle spacing) into the dies or rigid walls "
                  "(contact.penalty_scale = %.3g): the contact is soft, so the tools' forces read low and the part "
                  "passes into them; raise contact.penalty_scale (at the default 1 the test suite's runs stay under 0.08 of "
                  "a spacing)", counts.max_penetration, counts.max_penetration / counts.h_min, scene.contact.penalty_scale);
    s.warnings.push_back(text);
  }
  // Reference updates that smoothed away much of the kinetic energy (a strain of 1e-6 removed 13 % of the
  // Taylor bar's at 1.2 mm): the energy check leaves that work out of its balance
  double update_work = st.update_work;
  comm.sum(&update_work, 1);
  if (clock.energy_scale > 0 && std::abs(update_work) > kLostToUpdates * clock.energy_scale) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "reference updates took %.3g J of kinetic energy out of the run (%.2g %% of its energy scale; "
                  "reference_updates.strain = %.3g): the answer lost it; a larger strain updates less often",
                  -update_work, 100 * std::abs(update_work) / clock.energy_scale, scene.reference_updates.strain);
    s.warnings.push_back(text);
  }
  for (const auto& w : counts.warnings) s.warnings.push_back(w);
  s.presses = counts.presses;
  if (comm.rank() != 0) return s;
  for (const auto& p : s.presses) std::fprintf(stderr, "rksolve: %s\n", p.c_str());
  for (const auto& w : s.warnings) std::fprintf(stderr, "rksolve: warning: %s\n", w.c_str());
  for (const auto& w : scene_warnings(scene)) s.warnings.push_back(w);  // printed at the start
  for (const auto& w : counts.start_warnings) s.warnings.push_back(w);
  for (int p = 0; p < kPhaseCount; ++p) s.phases[kPhaseNames[p]] = {lo[p], hi[p]};
  const double loop_s = wall - counts.setup_s;
  s.steps = st.step;
  s.time = st.t;
  s.wall_s = wall;
  s.setup_s = counts.setup_s;
  s.ranks = comm.size();
  s.particles = std::int64_t(particles);
  s.integration_points = std::int64_t(points);
  s.neighbours_per_point = neighbours / std::max(points, 1.0);
  // the steps this run took (a restart or a stage goes on from a checkpoint's step)
  const double steps = double(st.step - counts.first_step);
  s.point_updates_per_s = loop_s > 0 ? points * steps / loop_s : 0.0;
  s.ns_per_point_update = steps > 0 ? 1e9 * loop_s * comm.size() / (points * steps) : 0.0;
  s.ns_per_particle_step = steps > 0 ? 1e9 * loop_s * comm.size() / (particles * steps) : 0.0;
  s.point_update_share = updates / std::max(points * (steps + 1), 1.0);  // (the last step updates the stress too)
  s.plastic_fraction = plastic / std::max(updates, 1.0);
  s.energy_error = clock.last_error;
  s.max_energy_error = clock.max_error;
  s.max_pressure_ratio = clock.max_pressure_ratio;
  s.impact_pressure_pa = counts.impact_pressure;
  s.ebc_method = scene.discretization.ebc_method;
  s.constraints = ebc.constraints();
  s.max_ebc_error_m = counts.max_ebc_error;
  s.initial_kinetic_energy = clock.kinetic0;
  s.viscous_work = sums[5];
  s.mass_scaling = md.mass_scaling;
  s.stable_step = scene.time.stable_step;
  s.step_ratio = st.step_ratio;
  s.max_kinetic_internal_ratio = clock.max_ke_ratio;
  s.reference_updates = st.reference_updates;
  s.thermal_updates = st.thermal_updates, s.thermal_step_s = st.thermal_dt;
  s.frames = counts.frames;
  s.peak_memory_mb_max_rank = mem_max;
  s.peak_bytes_per_point = mem_sum[0] * bytes_per_mb_point;
  s.resident_bytes_per_point = mem_sum[1] * bytes_per_mb_point;
  return s;
}

}  // namespace

RunSummary write_run_report(const std::string& case_dir, const Scene& scene, const Model& md, const State& st,
                            const RunClock& clock, const DieContact& dies, const EssentialBcs& ebc,
                            const PhaseTimer& timer, const RunCounts& counts, const Comm& comm) {
  const RunSummary s = summarize(scene, md, st, clock, dies, ebc, timer, counts, comm);
  // rank 0 writes; a failed write stops every rank with its message
  collectively(comm, [&] { return comm.rank() == 0 ? (write_run_summary(case_dir + "/solve.json", s), 0) : 0; });
  return s;
}

}  // namespace rk
