// CASE/solve.json, the contract between rksolve (the writer) and rkpost and the scripts (readers):
// what a finished run did, what it cost and whether to trust it. Written once, at the end of a run
// (a run a health check or a signal stopped has none); `format` is checked by the reader.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rk {

inline constexpr std::int64_t kRunSummaryFormat = 1;

struct PhaseTime {  // wall time of one phase of the step over the run, min and max over the ranks
  double min_s = 0, max_s = 0;
};

// A mass-scaled (quasi-static) run whose kinetic energy passes this share of the internal energy
// gets a warning: inertia, not the material, is carrying part of the load.
inline constexpr double kMaxQuasiStaticKineticRatio = 0.05;

struct RunSummary {
  std::int64_t format = kRunSummaryFormat;
  std::int64_t steps = 0;
  double time = 0;                 // simulated (s)
  double wall_s = 0, setup_s = 0;  // wall time of the whole run and of its set-up (s)
  std::int64_t ranks = 0, particles = 0, integration_points = 0;
  double neighbours_per_point = 0;  // at the end
  double point_updates_per_s = 0;
  double ns_per_point_update = 0;   // the figure of merit: loop wall time x ranks / (points x steps)
  double ns_per_particle_step = 0;  // loop wall time x ranks / (particles x steps): other meshfree codes' figure
  // the points updated per step over all points (1; below with multi-rate steps: time.subcycling)
  double point_update_share = 1;
  double plastic_fraction = 0;      // of the stress updates
  double energy_error = 0;          // at the end
  double max_energy_error = 0;      // the largest of the run (past its start-up)
  double max_pressure_ratio = 0;    // the largest |p| / (rho0 c_L v_max + sigma_y)
  double impact_pressure_pa = 0;    // rho0 c_L v_max
  std::string ebc_method;
  std::int64_t constraints = 0;     // constrained directions of the essential BCs, over all ranks
  double max_ebc_error_m = 0;
  double initial_kinetic_energy = 0, viscous_work = 0;  // J
  double mass_scaling = 1;
  std::string stable_step;  // time.stable_step
  double step_ratio = 0;    // with `frequency`: its step 2 / omega_max over the cells' estimate, at the end
  double max_kinetic_internal_ratio = 0;  // past 5 % of the run: a quasi-static run keeps it small
  std::int64_t reference_updates = 0, frames = 0;
  std::int64_t thermal_updates = 0;  // with heat conduction: the thermal updates of the run
  double thermal_step_s = 0;         // and the last stable thermal step
  double peak_memory_mb_max_rank = 0, peak_bytes_per_point = 0, resident_bytes_per_point = 0;
  std::map<std::string, PhaseTime> phases;  // by the phase names of the step (shared/phase_names.hpp)
  std::vector<std::string> warnings;        // suspicious but legal, also printed by rksolve
  std::vector<std::string> presses;         // how each die driven by its press ended (blows, energy, stroke)
};

void write_run_summary(const std::string& path, const RunSummary& summary);
// Throws rk::Error naming the file when it cannot be read or is of another format.
RunSummary read_run_summary(const std::string& path);

}  // namespace rk
