#include "io/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace rk {

Progress::Progress(bool show, int ranks, double now, double interval, double t0, double t_end,
                   const std::vector<std::string>& columns, const std::string& first_die, const State& st,
                   std::FILE* out)
    : show_(show), ranks_(ranks), out_(out), t0_(t0), t_end_(t_end), last_wall_(now), last_step_(st.step), last_t_(st.t) {
  // Under mpirun a rank's stdout is a pseudo-terminal even when mpirun's output goes to a file, so
  // the updating line is kept for runs started without a launcher; launched runs print plain lines.
  const bool launched = std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_RANK") || std::getenv("PMIX_RANK");
  terminal_ = !launched && ::isatty(::fileno(out)) != 0;
  interval_ = interval > 0 ? interval : terminal_ ? 2.0 : 10.0;
  if (!first_die.empty()) {
    const auto c = std::find(columns.begin(), columns.end(), first_die + ".stroke");
    if (c != columns.end()) press_column_ = c - columns.begin(), press_name_ = *c;
  }
}

void Progress::banner(bool restart, double setup_s, double mass_scaling, int subcycling) const {
  if (!show_) return;
  char rates[48] = "";
  if (subcycling > 1) std::snprintf(rates, sizeof rates, ", multi-rate steps up to %dx", subcycling);
  if (restart)
    std::fprintf(out_, "rksolve: %d ranks, restarted from the checkpoint of step %lld, t = %g s (setup %.2f s)%s, running to "
                "t = %g s\n", ranks_, static_cast<long long>(last_step_), last_t_, setup_s, rates, t_end_);
  else
    std::fprintf(out_, "rksolve: %d ranks, setup %.2f s, mass scaling %.3g%s, running to t = %g s\n", ranks_, setup_s,
                mass_scaling, rates, t_end_);
}

void Progress::step(const State& st, double dt, double energy_error, const std::vector<double>& history_row,
                    double now) {
  if (!show_ || now - last_wall_ <= interval_) return;
  const double rate = double(st.step - last_step_) / (now - last_wall_);
  // the ETA from the last interval's pace (simulated seconds per wall second), not the run's average,
  // which promises too little where the step keeps shrinking (docs/decisions.md, "The progress line's
  // ETA from the last interval's pace")
  const double pace = (st.t - last_t_) / (now - last_wall_);
  const double eta = pace > 0 ? (t_end_ - st.t) / pace : 0.0;
  last_wall_ = now;
  last_step_ = st.step;
  last_t_ = st.t;
  char press[96] = "";  // the first die's stroke and force, from the last history row
  if (press_column_ >= 0)
    std::snprintf(press, sizeof press, "  %s %.4g mm, %.4g kN", press_name_.c_str(),
                  1e3 * history_row[std::size_t(press_column_)], 1e-3 * history_row[std::size_t(press_column_) + 1]);
  // a terminal gets one updating line; a pipe or a log gets a plain line
  std::fprintf(out_, "%srksolve: t = %.4g s (%5.1f %%)  step %lld  %.0f steps/s  dt = %.3g s%s  energy error %.2e  ETA %.0f s%s",
              terminal_ ? "\r" : "", st.t, 100 * (st.t - t0_) / (t_end_ - t0_), static_cast<long long>(st.step), rate, dt, press,
              energy_error, eta, terminal_ ? "   " : "\n");
  std::fflush(out_);
  line_open_ = terminal_;
}

void Progress::done(std::int64_t steps, double wall_s, double ns_per_point_update, double ns_per_particle_step,
                    double energy_error) const {
  if (!show_) return;
  if (line_open_) std::fprintf(out_, "\n");
  std::fprintf(out_, "rksolve: done, %lld steps, %.2f s wall (%.0f ns per point update, %.0f per particle step), "
              "energy error %.2e\n", static_cast<long long>(steps), wall_s, ns_per_point_update, ns_per_particle_step,
              energy_error);
}

}  // namespace rk
