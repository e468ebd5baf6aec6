// The run's report, CASE/solve.json (shared/run_summary.hpp): what the run did, what it cost per
// phase and per integration-point update, its memory, and whether to trust it (the largest energy
// error and pressure ratio, warnings about suspicious but legal input), gathered over the ranks at
// the end of the run. Rank 0 writes it and prints the warnings.
#pragma once
#include <string>
#include <vector>
#include <string>

#include "boundary/essential_bc.hpp"
#include "contact/die_contact.hpp"
#include "io/checkpoint.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "phase_timer.hpp"
#include "run_summary.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

// What the time loop counted besides the state and the clock.
struct RunCounts {
  double wall0 = 0, setup_s = 0;  // the run's start (Comm::wtime) and its set-up time (s)
  double baseline_mb = 0;         // resident memory before any data: the program and its libraries
  double plastic_updates = 0, point_updates = 0;  // this rank's stress updates, and those that were plastic
  double max_ebc_error = 0;       // the essential BCs' largest violation seen (m)
  double max_penetration = 0;     // the material's deepest point inside a die or rigid wall seen (m)
  double h_min = 0;               // the smallest particle spacing (m)
  double v_start = 0;             // the fastest start or tool (m/s; HealthScales)
  double impact_pressure = 0;     // rho0 c_L v_max (Pa)
  std::int64_t frames = 0;
  std::int64_t first_step = 0;  // the step this run started from (0, or a checkpoint's)
  std::vector<std::string> presses;         // how each press-driven die ended (the same on every rank)
  std::vector<std::string> warnings;        // the presses that stalled short of their stroke
  std::vector<std::string> start_warnings;  // found (and printed) at the start
};

// Collective; returns the summary (complete on rank 0) after writing it to CASE/solve.json.
RunSummary write_run_report(const std::string& case_dir, const Scene& scene, const Model& md, const State& st,
                            const RunClock& clock, const DieContact& dies, const EssentialBcs& ebc,
                            const PhaseTimer& timer, const RunCounts& counts, const Comm& comm);

}  // namespace rk
