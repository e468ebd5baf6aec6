// What rksolve prints while it runs (rank 0, not with --quiet): a banner, a progress line every 2 s
// on a terminal (one updating line) or every 10 s into a pipe or a log (--progress SECONDS sets
// the interval), and a closing line.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "state.hpp"

namespace rk {

class Progress {
 public:
  // show: rank 0 and not --quiet; now: the wall clock (s); interval: seconds between lines (0: 2 s
  // on a terminal, 10 s otherwise); the run from t0 (0, or a stage's start) to t_end; columns: the
  // history's, the line shows the first die's stroke and force from the last row.
  Progress(bool show, int ranks, double now, double interval, double t0, double t_end,
           const std::vector<std::string>& columns, const std::string& first_die, const State& st,
           std::FILE* out = stdout);

  // subcycling: time.subcycling as resolved (the largest ratio of a particle's step to the smallest)
  void banner(bool restart, double setup_s, double mass_scaling, int subcycling) const;
  // After a step, at wall time `now`: prints when the interval has passed.
  void step(const State& st, double dt, double energy_error, const std::vector<double>& history_row, double now);
  // steps: this run's (a restart's or a stage's own)
  void done(std::int64_t steps, double wall_s, double ns_per_point_update, double ns_per_particle_step,
            double energy_error) const;

 private:
  bool show_;
  int ranks_;
  std::FILE* out_;
  double t0_, t_end_;
  bool terminal_;        // one updating line (a terminal, no launcher), else plain lines
  double interval_;
  bool line_open_ = false;  // an updating line is on the terminal: end it before other output
  std::string press_name_;   // the first die's stroke column, empty without dies
  std::ptrdiff_t press_column_ = -1;
  double last_wall_;
  std::int64_t last_step_;
  double last_t_;
};

}  // namespace rk
