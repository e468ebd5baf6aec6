// rksolve's time loop: explicit central differences on the RKPM semi-discretization (Wang et al. 2007, Fig. 5),
// the step as a sequence of named phases (Simulation::run), each timed under its own name.
#include "solver.hpp"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "boundary/essential_bc.hpp"
#include "contact/die_contact.hpp"
#include "contact/die_fill.hpp"
#include "contact/part_contact.hpp"
#include "contact/presses.hpp"
#include "energy.hpp"
#include "error.hpp"
#include "health.hpp"
#include "highest_frequency.hpp"
#include "case_lock.hpp"
#include "io/checkpoint.hpp"
#include "io/run_scene.hpp"
#include "io/history.hpp"
#include "io/point_tracks.hpp"
#include "io/output.hpp"
#include "io/progress.hpp"
#include "io/run_report.hpp"
#include "material/bulk_viscosity.hpp"
#include "material/damage.hpp"
#include "material/stress_update.hpp"
#include "model.hpp"
#include "parallel/overlap_exchange.hpp"
#include "phase_timer.hpp"
#include "process_memory.hpp"
#include "rk/internal_force.hpp"
#include "rk/kinematics.hpp"
#include "rk/reference_update.hpp"
#include "run_summary.hpp"
#include "running_extrema.hpp"
#include "state.hpp"
#include "step_limits.hpp"
#include "subcycles.hpp"
#include "stage.hpp"
#include "subdomain.hpp"
#include "thermal/heat_transfer.hpp"
#include "time_step.hpp"

namespace rk {
namespace {

// A dwell's thermal strain worth a warning (the shape is held while the temperature moves): 1e-4, 7 K of
// steel's expansion, 0.01 mm over 100 mm
constexpr double kDwellHeldStrain = 1e-4;

// The value of `column` in the first row of the CSV file at `path`, or `fallback` where it cannot be read
double first_row_value(const std::string& path, const std::string& column, double fallback) {
  std::ifstream in(path);
  std::string header, row;
  if (!std::getline(in, header) || !std::getline(in, row)) return fallback;
  std::istringstream names(header), values(row);
  std::string name, value;
  while (std::getline(names, name, ',') && std::getline(values, value, ','))
    if (name == column) return std::strtod(value.c_str(), nullptr);
  return fallback;
}

// Ctrl-C (SIGINT) or a job scheduler's SIGTERM: the run stops at the next step on every rank, after
// writing a checkpoint and a frame, so that --restart goes on from there.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void request_stop(int signal) { g_interrupted = signal; }

class Simulation {
 public:
  Simulation(const SolveOptions& opt, const Comm& comm);  // set-up: the model, the state at t = 0 (or restart)
  void run();                                             // the time loop (or the dwell's)
  void finish();                                          // solve.json, warnings, the closing line

 private:
  // the phases of a step, in the order run() calls them
  bool update_due() const;
  void reference_update();
  bool checkpoint_due(bool last) const;
  bool checkpoint_clock() const;
  void checkpoint();
  [[noreturn]] void stop_on_interrupt();
  void subcycle();
  void deformation_gradient();
  void stress_update();
  void contact();
  void time_step();
  void check_health() const;
  double step_size(bool last);
  bool heat_due(double dt, bool last) const;
  void heat_transfer();
  void internal_force();
  void velocity_update(double dt, double dt_avg);
  void press(double dt_avg);
  void constraints(double dt, double dt_avg);
  void boundary_work(double dt_avg);
  bool history_due(bool last) const;
  void history(double dt, bool last);
  bool output_due(bool last) const;
  void output(double dt);
  void displacement_update(double dt);

  void dwell();  // a stage in which nothing moves the part: the temperature alone, at the thermal step
  void warn_if_moving(const Comm& comm);  // a dwell that sets down a part in motion
  double mean_temperature() const;        // collective
  void start_presses(double h_min);
  void check_reach();
  void rebind();  // after a reference update: what is sized by the rank's local particles
  void start_subcycles();
  void write_frame(const std::vector<double>& velocity);

  const SolveOptions& opt_;
  const Comm& comm_;
  double wall0_, baseline_mb_, setup_s_ = 0;
  Scene scene_;
  Model md_;      // offline data (rebuilt only by a reference update)
  State st_;      // the state at t^n (what a checkpoint holds, with clock_ and the dies' totals)
  RunClock clock_;
  std::unique_ptr<EssentialBcs> ebc_;
  std::unique_ptr<DieContact> dies_;
  std::unique_ptr<PartContact> parts_;  // the part with itself and between bodies
  std::unique_ptr<Presses> presses_;    // with dies driven by their press only
  std::unique_ptr<DieFill> fill_;       // with dies only
  std::unique_ptr<HeatTransfer> heat_;  // with conduction only
  std::unique_ptr<ResultWriter> results_;
  std::unique_ptr<History> history_;
  std::unique_ptr<PointTracks> tracks_;
  std::unique_ptr<HealthChecks> health_;
  std::unique_ptr<HighestFrequency> frequency_;  // with time.stable_step = frequency only
  // with time.subcycling > 1 only: the classes, this step's (sync_: every point and particle due, the
  // cycle's first step), the cells' steps at its start and the cycle's dt; the contact's forces apart
  // (they act at every step), and each particle's dt_avg this step (0: not due)
  std::unique_ptr<Subcycles> subcycles_;
  bool sync_ = true;
  int level_ = 0;
  std::vector<double> cell_dt_;
  double cycle_dt_ = 0;
  std::vector<Fixed> contact_partial_;
  std::vector<double> contact_force_, particle_dt_avg_;
  std::unique_ptr<Progress> progress_;
  std::optional<OverlapExchange> exchange_;
  WriteLastFrame last_frame_;
  PhaseTimer timer_;
  PressureBound pressure_bound_;
  int headroom_ = 0;  // of the fixed-point force sums: their resolution (raised in a step that needs it)
  ForceTerms force_terms_;  // the most terms of each kind a particle's force sum receives
  int die_headroom_ = 0;  // of the dies' own sums (their loads, a ram's reaction)
  std::vector<double> v_old_;  // v^{n-1/2} during the step (v^n at an output)
  std::int64_t first_step_ = 0;
  double t0_ = 0;  // the run's start on the chain's clock: 0, or a stage's start
  StageLink stage_;
  bool staged_ = false, dwell_ = false;  // a stage of a chain; one without dies, loads or moving faces
  // what one step hands the next phases
  StressHealth stress_;
  StableStep stable_{};
  double contact_bound_ = 0;
  bool healthy_ = true;
  StepLimits limits_;  // the last step's: they decide the next step's reference update, checkpoint, stop
  double last_checkpoint_wall_ = 0;
  std::int64_t last_checkpoint_step_ = 0;
  double plastic_updates_ = 0, point_updates_ = 0;  // this run's stress updates, and those that were plastic
  double max_ebc_error_ = 0;
  double max_penetration_ = 0;  // over this run's history rows (m)
  std::vector<std::string> start_warnings_;  // found at the start, also in solve.json
  std::vector<std::string> run_warnings_;    // found during the run, printed at its end
};

// The step, t^n -> t^{n+1}: positions at t^n and velocities v^{n-1/2} in, both one step on out.
void Simulation::run() {
  // rkpost's outputs and the scripts' (vtk/, plots/, report.md) are of the results this run replaces or extends,
  // removed once it is set to go (a refused start leaves the case as it was): a report kept across a new run gave
  // the old run's footprint and linked its pictures
  if (comm_.rank() == 0)
    for (const char* derived : {"vtk", "plots", "report.md"}) std::filesystem::remove_all(opt_.case_dir + "/" + derived);
  if (dwell_) return dwell();
  for (;;) {
    timer_.start();
    // the end within 1e-12 of it (the round-off of the summed steps), or every ram at rest
    const bool last = st_.t >= scene_.time.end * (1 - 1e-12) || (presses_ && presses_->stopped(st_));
    subcycle();                                 // with multi-rate steps: whether a cycle starts, the classes due
    if (update_due()) reference_update();       // the current configuration becomes the reference
    if (checkpoint_due(last)) checkpoint();     // t^n, v^{n-1/2}
    if (limits_.interrupted && sync_) stop_on_interrupt();  // a rank was interrupted: every rank stops here
    deformation_gradient();                     // F = I + sum_I d_I (x) grad_X N_I at the points
    stress_update();                            // bulk viscosity, J2 return map with F-bar, P = tau F^-T
    contact();                                  // the dies', walls' and symmetry planes' forces
    time_step();                                // the step's one reduction over ranks
    check_health();                             // a state that is not physical stops every rank here
    const double dt = step_size(last);
    timer_.stop(kTimeStep);                     // (with the health checks and a cycle's plan: not the force's)
    const double dt_avg = st_.step == 0 ? 0.5 * dt : 0.5 * (st_.dt_half + dt);
    if (heat_due(dt, last)) heat_transfer();    // conduction and surface heat from the last update to t^n
    internal_force();                           // f = sum_g w_g P_g grad_X N_I - f_contact, overlap summed
    velocity_update(dt, dt_avg);                // v^{n+1/2} = v^{n-1/2} + dt_avg (g - f / m)
    if (presses_) press(dt_avg);                // the rams' v^{n+1/2} from the part's reaction
    constraints(dt, dt_avg);                    // the essential BCs at t^{n+1}
    boundary_work(dt_avg);                      // the contact's and the body force's work over the step
    if (history_due(last)) history(dt, last);   // a history row at t^n, its health checks
    if (output_due(last)) output(dt);           // a frame at t^n, v^n between v^{n-1/2} and v^{n+1/2}
    if (last) break;
    displacement_update(dt);                    // d^{n+1} = d^n + dt v^{n+1/2}, t^{n+1}
    progress_->step(st_, dt, clock_.last_error, history_->row(), comm_.wtime());
  }
}

// A dwell: nothing moves the part (no dies, loads or moving faces; its velocities were set to zero),
// so only its temperature advances, one thermal stable step at a time, landing on the output times;
// without heat conduction, straight to the end. The stress at the start (the previous stage's
// last, which its checkpoint leaves to the next step) is the dwell's.
void Simulation::dwell() {
  timer_.start();
  deformation_gradient();
  stress_update();
  const double entered = mean_temperature();  // (the stage's start, unless this is a restart within the dwell)
  for (;;) {
    timer_.start();
    const bool last = st_.t >= scene_.time.end * (1 - 1e-12);
    limits_.checkpoint_clock = checkpoint_clock();  // the step's flags over the ranks, as time_step() does
    limits_.interrupted = g_interrupted != 0;
    limits_.reduce(comm_);
    if (checkpoint_due(last)) checkpoint();
    if (limits_.interrupted) stop_on_interrupt();
    if (history_due(last)) history(0.0, last);
    if (output_due(last)) output(0.0);
    if (last) break;
    double dt = scene_.time.end - st_.t;
    if (heat_) dt = std::min(dt, st_.thermal_dt);
    if (clock_.next_output - st_.t > 1e-9 * scene_.time.output_interval) dt = std::min(dt, clock_.next_output - st_.t);
    st_.t += dt;  // dt_half stays the last mechanical step's: the next stage's first step averages with it
    ++st_.step;
    if (heat_) heat_transfer();
    progress_->step(st_, dt, clock_.last_error, history_->row(), comm_.wtime());
  }
  // The shape and the stresses are held while the temperature moves: a part that cooled or heated by much
  // is told that its thermal strain (and any springback) waits for the next stage's first step (a 600 s
  // dwell of the hot upsetting in air: 1284 -> 486 K, the radius held where it would shrink 1.1 %)
  if (md_.thermal_strain()) {
    // from the stage's start: its first history row (rank 0 keeps the rows before a restart; the others'
    // warnings are not reported)
    const double T0 = comm_.rank() == 0 ? first_row_value(opt_.case_dir + "/history.csv", "temperature_mean", entered) : entered;
    const double T1 = mean_temperature(), stretch = md_.thermal_stretch(T1) / md_.thermal_stretch(T0) - 1;
    if (std::abs(stretch) > kDwellHeldStrain) {
      char text[400];
      std::snprintf(text, sizeof text, "the dwell moved the part's mean temperature from %.1f K to %.1f K with its shape and "
                    "stresses held as at its start (a dwell advances the temperature alone): its thermal %s of %.2g %% "
                    "(and any springback) is released at the next stage's first step, so the part's dimensions and "
                    "stresses here are those of the dwell's start", T0, T1, stretch < 0 ? "contraction" : "expansion",
                    100 * std::abs(stretch));
      run_warnings_.push_back(text);
    }
  }
}

// The part's mean temperature (K): its points' weighted over every rank; 0 without a temperature
double Simulation::mean_temperature() const {
  double sums[2] = {0, 0};
  for (std::size_t g = 0; g < st_.temperature.size(); ++g) sums[0] += md_.weight[g] * st_.temperature[g], sums[1] += md_.weight[g];
  comm_.sum(sums, 2);
  return sums[1] > 0 ? sums[0] / sums[1] : 0.0;
}

// A dwell sets the part down: said where it still moves as a dynamic event does (an impact's bar in
// flight), not as a formed part at rest (kinetic energy within the quasi-static bound of its internal).
void Simulation::warn_if_moving(const Comm& comm) {
  const Energies e = compute_energies(md_, st_, st_.v, comm);
  if (!(e.kinetic > kMaxQuasiStaticKineticRatio * e.internal)) return;
  char text[400];
  std::snprintf(text, sizeof text, "this stage has no dies, loads or moving faces, so it is a dwell that sets the part "
                "down, but the part moves: %.3g J of kinetic energy against %.3g J internal (a formed part at rest "
                "has under 5 %%); `--set time.dwell=off` goes on with its motion", e.kinetic, e.internal);
  start_warnings_.push_back(text);
  if (comm.rank() == 0) std::fprintf(stderr, "rksolve: warning: %s\n", text);
}

bool Simulation::update_due() const {
  const double strain = scene_.reference_updates.strain;
  return sync_ && strain > 0 && limits_.strain_since_update > strain;
}

void Simulation::reference_update() {
  const Projection project = [&](std::size_t I, double* x) { ebc_->project(md_, I, st_.t, x); };
  collectively(comm_, [&] { return update_reference(md_, st_, scene_, comm_, project), 0; });
  rebind();
  st_.step_ratio = 0;  // the stable step's frequency afresh on the new shapes (the mode carried over)
  if (heat_) heat_->reproject(md_, st_, comm_);  // the heat content kept on the new shapes
  clock_.dt_penalty = -1;  // the new configuration's steps set the penalty afresh (contact_laws.hpp)
  timer_.stop(kReferenceUpdate);
}

bool Simulation::checkpoint_due(bool last) const {
  const auto every = scene_.output.checkpoint_steps;
  if (!sync_) return false;  // (multi-rate steps: a due checkpoint waits for the cycle's end)
  const bool steps = every > 0 && (subcycles_ ? st_.step / every > last_checkpoint_step_ / every : st_.step % every == 0);
  return (steps && st_.step > first_step_) || last || limits_.checkpoint_clock ||
         limits_.interrupted;  // a stop writes a checkpoint first
}

void Simulation::checkpoint() {
  last_checkpoint_wall_ = comm_.wtime();
  last_checkpoint_step_ = st_.step;
  clock_.frames = results_->frames();
  collectively(comm_, [&] { return write_checkpoint(opt_.case_dir, md_, st_, clock_, *dies_), 0; });
  timer_.stop(kCheckpoint);
}

void Simulation::stop_on_interrupt() {
  deformation_gradient();  // the frame's stresses are this state's (t^n)
  stress_update();
  write_frame(st_.v);
  std::ostringstream why;
  why << "interrupted at step " << st_.step << ", t = " << st_.t << " s: checkpoint and last frame written; `rksolve "
      << opt_.case_dir << " --restart` goes on from here";
  throw Error(why.str());
}

// Multi-rate steps (subcycles.hpp): a cycle starts when the last one has run its course; otherwise
// the classes due at this step's offset in it.
void Simulation::subcycle() {
  if (!subcycles_) return;
  sync_ = subcycles_->starts(st_.step);
  if (!sync_) level_ = subcycles_->level(st_.step);
}

void Simulation::deformation_gradient() {
  if (sync_) compute_deformation_gradient(md_, st_);
  else compute_deformation_gradient(md_, st_, subcycles_->cells(level_));
  timer_.stop(kDeformationGradient);
}

void Simulation::stress_update() {
  if (!subcycles_) {
    update_bulk_viscosity(md_, st_, scene_.bulk_viscosity);
    stress_ = update_stress(md_, st_, pressure_bound_);
    point_updates_ += double(md_.m);
  } else {  // the cells due, each over its own increment since its last update
    const std::span<const std::int32_t> due = sync_ ? subcycles_->all_cells() : subcycles_->cells(level_);
    update_bulk_viscosity(md_, st_, scene_.bulk_viscosity, due);
    stress_ = update_stress(md_, st_, pressure_bound_, due);
    for (const std::int32_t c : due) st_.cell_t_last[std::size_t(c)] = st_.t;
    point_updates_ += sync_ ? double(md_.m)
                            : double(subcycles_->boundary_points(level_).size() + subcycles_->interior_points(level_).size());
  }
  plastic_updates_ += double(stress_.plastic);
  timer_.stop(kStressUpdate);
}

void Simulation::contact() {
  if (presses_) presses_->place(st_, *dies_, false);  // the rams at s^n, v^{n-1/2}
  // the penalty's step: the smallest since the start or the last reference update (< 0 just after one)
  const double dt_min = clock_.dt_penalty > 0 ? clock_.dt_penalty : clock_.dt_stable;
  contact_bound_ = dies_->compute(md_, st_, st_.t, clock_.dt_stable, dt_min);
  contact_bound_ = std::max(contact_bound_, parts_->compute(md_, st_, clock_.dt_stable, dt_min, comm_));
  timer_.stop(kContact);
}

// The stable step, the force bound, and what decides the next steps, agreed over the ranks at once.
void Simulation::time_step() {
  // the points' largest force bound, and the contact's
  const double bound = largest_of(md_.m, contact_bound_, [&](std::size_t g) { return st_.force_bound[g]; });
  healthy_ = stress_.ok && std::isfinite(bound);
  // and after a reference update the contact's step, on the new reference's edges: its stiffness keeps to
  // it, the step grows at most step_growth times past it (time_step.hpp, contact/contact_laws.hpp); the
  // step from the highest frequency is the contact's own (the ratio below undoes any growth)
  limits_.penalty_dt = std::numeric_limits<double>::infinity();  // (dt itself, before an update)
  if (sync_)
    stable_ = stable_time_step(md_, st_, scene_.time.cfl, true, stable_.cell, frequency_ ? nullptr : &limits_.penalty_dt);
  if (subcycles_ && sync_)  // whether any cell could take more than the smallest step
    limits_.cell_dt_ceiling = cell_time_step_ceiling(md_, st_, scene_.time.cfl);
  if (frequency_) stable_.dt *= frequency_->step_ratio(md_, st_, comm_);  // the same on every rank
  const double update_strain = scene_.reference_updates.strain;
  limits_.dt = stable_.dt;
  limits_.force_bound = bound;
  limits_.contact_bound = contact_bound_;
  limits_.unhealthy = !healthy_;
  limits_.checkpoint_clock = checkpoint_clock();
  limits_.strain_since_update = update_strain > 0 ? 0.5 * std::sqrt(stress_.green_strain2) : 0.0;  // the largest |E|
  limits_.symmetry_depth = dies_->symmetry_depth() / health_->scales().h_min;
  limits_.pressure_ratio = stress_.pressure_ratio;
  limits_.interrupted = g_interrupted != 0;
  limits_.reaction_bound = presses_ ? presses_->reaction_bound(*dies_) : 0.0;
  limits_.reduce(comm_);
  clock_.max_pressure_ratio = std::max(clock_.max_pressure_ratio, limits_.pressure_ratio);
  timer_.stop(kTimeStep);
}

// Rank 0's clock decides whether a wall-clock checkpoint is due (written at the next step's top).
bool Simulation::checkpoint_clock() const {
  return comm_.rank() == 0 && scene_.output.checkpoint_minutes > 0 &&
         comm_.wtime() - last_checkpoint_wall_ >= 60 * scene_.output.checkpoint_minutes;
}

void Simulation::check_health() const {
  health_->after_reduction(md_, st_, *dies_, limits_, stable_, stress_, healthy_, comm_, last_frame_);
}

// The stable step, shortened to land on the end and on the next output time (an output time within
// 1e-9 of the interval counts as reached: the clock's round-off).
double Simulation::step_size(bool last) {
  double dt = limits_.dt;
  clock_.dt_stable = dt;
  const double penalty_dt = std::min(limits_.penalty_dt, dt);
  clock_.dt_penalty = clock_.dt_penalty > 0 ? std::min(clock_.dt_penalty, penalty_dt) : penalty_dt;
  const double out_dt = scene_.time.output_interval;
  if (!last) {
    dt = std::min(dt, scene_.time.end - st_.t);
    if (clock_.next_output - st_.t > 1e-9 * out_dt) dt = std::min(dt, clock_.next_output - st_.t);
  }
  if (!subcycles_) return dt;
  if (!sync_) return cycle_dt_;
  // a cycle of 2^levels steps that ends on or before the end and the next output time (the one after
  // this step's frame where one is due now); none where the step was shortened to land
  const double next_output = clock_.next_output + (output_due(last) ? out_dt : 0.0);
  const double horizon = std::min(scene_.time.end, next_output) - st_.t;
  int levels = 0;
  while (levels < subcycles_->max_levels() && !last && dt == limits_.dt && double(2 << levels) * dt <= horizon) ++levels;
  if (limits_.cell_dt_ceiling < 2 * dt) levels = 0;  // every cell at the smallest step: no classes to count
  if (levels > 0)  // each cell's own step, as far as its class needs (a cycle holds the step of its start)
    cell_time_steps(md_, st_, scene_.time.cfl, dt, levels, cell_dt_);
  subcycles_->plan(md_, cell_dt_, dt, levels, st_.step, [&](std::vector<Fixed>& counts) { exchange_->sum(counts); },
                   [&](int k) {
                     double top = k;
                     comm_.max(&top, 1);
                     return int(top);
                   });
  level_ = subcycles_->level(st_.step);
  cycle_dt_ = dt;
  return dt;
}

// As the temperature's stable step and thermal.max_steps_per_update require (thermal/heat_transfer.hpp),
// and before every frame: a frame shows the temperature at t^n. (Not at the history rows: their
// spacing, time.end / 500, would make the answer depend on time.end.)
bool Simulation::heat_due(double dt, bool last) const {
  return heat_ && (heat_->due(st_, dt) || output_due(last));
}

void Simulation::heat_transfer() {
  heat_->update(md_, st_, *dies_, comm_);
  timer_.stop(kHeatTransfer);
}

// In fixed point: the boundary points'' and the contacts' partials travel while the interior's are computed.
void Simulation::internal_force() {
  const int headroom = step_headroom(headroom_, force_terms_, limits_.force_bound, limits_.contact_bound);
  const FixedScale scale = FixedScale::for_bound(limits_.force_bound, headroom);
  clear_internal_force(st_);
  using Points = std::span<const std::int32_t>;
  const bool all = sync_ || !subcycles_;  // (multi-rate steps: the points due)
  const Points boundary = all ? Points(md_.boundary_points) : subcycles_->boundary_points(level_);
  const Points interior = all ? Points(md_.interior_points) : subcycles_->interior_points(level_);
  add_internal_force(md_, st_, scale, boundary);
  // multi-rate steps: the contact's own sums (it acts at every step, the internal force at each particle's)
  std::vector<Fixed>& contact = subcycles_ ? contact_partial_ : st_.partial;
  if (subcycles_) std::fill(contact_partial_.begin(), contact_partial_.end(), Fixed(0));
  dies_->add_to(md_, contact, scale);  // die contact forces of the owned particles and points, once over all ranks
  parts_->add_to(md_, contact, scale);
  if (subcycles_) {
    exchange_->sum(contact_partial_);
    read_forces(contact_partial_, scale, contact_force_);
    subcycles_->touch(contact_force_);
  }
  timer_.stop(kInternalForce);
  exchange_->start(st_.partial);
  timer_.stop(kOverlapExchange);
  add_internal_force(md_, st_, scale, interior);
  timer_.stop(kInternalForce);
  exchange_->finish(st_.partial);
  read_forces(st_.partial, scale, st_.force);
  timer_.stop(kOverlapExchange);
}

void Simulation::velocity_update(double dt, double dt_avg) {
  std::copy(st_.v.begin(), st_.v.end(), v_old_.begin());
  const double* g = scene_.loads.gravity.data();
  if (!subcycles_) {
    for (std::size_t I = 0; I < md_.n; ++I)
      for (int i = 0; i < 3; ++i) st_.v[3 * I + i] += dt_avg * (g[i] - st_.force[3 * I + i] / md_.mass[I]);
  } else {  // the contact at every step; the internal force and the body force over a due particle's own step
    for (std::size_t I = 0; I < md_.n; ++I) {
      const double* fc = &contact_force_[3 * I];  // (+0 where no contact: read from fixed point)
      if (fc[0] != 0 || fc[1] != 0 || fc[2] != 0)
        for (int i = 0; i < 3; ++i) st_.v[3 * I + i] -= dt_avg * fc[i] / md_.mass[I];
      const int k = subcycles_->particle_class(I);
      particle_dt_avg_[I] = 0;
      if (!sync_ && k > level_) continue;
      const double span = double(1 << k) * dt, own = 0.5 * (st_.particle_dt_half[I] + span);
      for (int i = 0; i < 3; ++i) st_.v[3 * I + i] += own * (g[i] - st_.force[3 * I + i] / md_.mass[I]);
      st_.particle_dt_half[I] = span;
      particle_dt_avg_[I] = own;
    }
  }
  timer_.stop(kVelocityUpdate);
}

void Simulation::press(double dt_avg) {
  presses_->advance(st_, *dies_, limits_.reaction_bound, dt_avg, comm_);
  presses_->place(st_, *dies_, true);  // the step's mean speed, for the work
  timer_.stop(kPress);
}

void Simulation::constraints(double dt, double dt_avg) {
  ebc_->apply(md_, st_, st_.t + dt, dt, dt_avg, v_old_);
  timer_.stop(kConstraints);
}

void Simulation::boundary_work(double dt_avg) {
  dies_->account(md_, st_, v_old_, dt_avg, st_.t);
  parts_->account(md_, st_, v_old_, dt_avg);
  const double* g = scene_.loads.gravity.data();
  if (norm(scene_.loads.gravity) > 0)  // work of the body force on the owned particles
    for (std::size_t I = 0; I < md_.n; ++I)
      if (md_.owned[I])
        for (int i = 0; i < 3; ++i)
          st_.external_work += (subcycles_ ? particle_dt_avg_[I] : dt_avg) * md_.mass[I] * g[i] * 0.5 *
                               (v_old_[3 * I + i] + st_.v[3 * I + i]);
  timer_.stop(kBoundaryWork);
}

// A row every 1/500 of the run (io/history.hpp), due within 1e-9 of that: the clock's round-off.
bool Simulation::history_due(bool last) const {
  const double hist_dt = (scene_.time.end - t0_) / 500;
  return last || (sync_ && st_.t >= clock_.next_history - 1e-9 * hist_dt);
}

void Simulation::history(double dt, bool last) {
  static const std::vector<double> none;
  const std::vector<double>& filled = fill_ ? fill_->filled(*dies_, comm_) : none;
  const HistoryRow row = history_->record(md_, st_, *dies_, *parts_, filled, *ebc_, v_old_, dt, clock_.kinetic0,
                                             clock_.energy_scale, comm_);
  tracks_->record(md_, st_, comm_);
  const double t_end = scene_.time.end, run = t_end - t0_;  // the run's end and length (a stage's own)
  max_ebc_error_ = std::max(max_ebc_error_, row.ebc_error);
  max_penetration_ = std::max(max_penetration_, row.penetration);
  clock_.last_error = row.energy_error;
  // past the start-up (docs/decisions.md, "The energy check skips the start-up"): the first 100
  // steps, and for a part that starts at rest (its energy scale grows from 0 with the tools' work)
  // the first 10 % of the run. KE / internal counts past 5 % of the run, once the internal energy
  // has formed.
  const bool started = st_.step >= 100 && (clock_.kinetic0 > 0 || st_.t > t0_ + 0.1 * run);
  if (started || last) clock_.max_error = std::max(clock_.max_error, row.energy_error);
  if (st_.t > t0_ + 0.05 * run) clock_.max_ke_ratio = std::max(clock_.max_ke_ratio, row.kinetic_internal);
  if (st_.t > t0_ + 0.5 * run) clock_.max_ke_ratio_late = std::max(clock_.max_ke_ratio_late, row.kinetic_internal);
  clock_.next_history += run / 500;
  // (multi-rate steps: a row waits for a cycle's start; the rows it passed are not caught up later)
  while (subcycles_ && clock_.next_history <= st_.t + 1e-9 * run / 500) clock_.next_history += run / 500;
  health_->after_history(md_, st_, *dies_, row.energy_error, started, comm_, last_frame_);
  timer_.stop(kHistory);
}

// Due within 1e-9 of the interval, as history_due.
bool Simulation::output_due(bool last) const {
  return last || (sync_ && st_.t >= clock_.next_output - 1e-9 * scene_.time.output_interval);
}

// The frame's velocity at t^n: v^{n-1/2} and v^{n+1/2} (at t^n less half the last step and plus half
// this one) interpolated linearly in time, v^{n-1/2} + (dt^{n-1/2} / 2) a^n. With multi-rate steps each
// particle's own last and next spans, so a frame does not depend on the steps that follow it (a frame
// in the middle of a run and the last frame of a run ending there agree). dt = 0 (a dwell: nothing
// moves): v itself.
void Simulation::output(double dt) {
  for (std::size_t I = 0; I < md_.n; ++I) {
    double w = 1;  // the weight of v^{n+1/2}
    if (subcycles_ && dt > 0) {  // (at a cycle's start every particle is due: own = (last + next span) / 2)
      const double own = particle_dt_avg_[I], next = st_.particle_dt_half[I];
      w = own > 0 ? (2 * own - next) / (2 * own) : 0.0;
    } else if (dt > 0) {
      w = st_.dt_half / (st_.dt_half + dt);
    }
    for (int i = 0; i < 3; ++i) v_old_[3 * I + i] += w * (st_.v[3 * I + i] - v_old_[3 * I + i]);
  }
  write_frame(v_old_);
  clock_.next_output += scene_.time.output_interval;
  timer_.stop(kOutput);
}

void Simulation::displacement_update(double dt) {
  for (std::size_t k = 0; k < st_.u.size(); ++k) st_.u[k] += dt * st_.v[k];
  if (presses_) presses_->move(st_, dt);
  st_.t += dt;
  st_.dt_half = dt;
  ++st_.step;
  timer_.stop(kDisplacementUpdate);
}

// Output is collective; a failure on any rank (disk full, unwritable directory) stops every rank.
void Simulation::write_frame(const std::vector<double>& velocity) {
  const DieFrame dies = fill_ ? fill_->frame(*dies_, st_.t, comm_) : DieFrame{};
  collectively(comm_, [&] { return results_->write_frame(md_, st_, velocity, comm_, dies), 0; });
}

// Multi-rate steps on this model: the classes (planned at the first step) and the per-particle arrays.
void Simulation::start_subcycles() {
  subcycles_ = std::make_unique<Subcycles>(md_, scene_.time.subcycling);
  contact_partial_.assign(st_.partial.size(), 0);
  contact_force_.assign(3 * md_.n, 0.0);
  particle_dt_avg_.assign(md_.n, 0.0);
}

void Simulation::rebind() {
  const int die_count = int(md_.dies.size());
  ebc_ = collectively(comm_, [&] { return std::make_unique<EssentialBcs>(md_, scene_, comm_); });
  const std::vector<DieTotals> totals = dies_->totals();
  const std::vector<std::int64_t> touched = dies_->touched();  // the die fill stays
  const std::vector<double> sticks = dies_->stick_rows();  // and the friction's sticks
  dies_ = std::make_unique<DieContact>(md_, scene_, md_.dies, dies_.get());
  dies_->totals() = totals;
  dies_->touched() = touched;
  dies_->set_stick_rows(sticks, "the reference update");
  parts_ = std::make_unique<PartContact>(md_, scene_, comm_);
  exchange_.emplace(md_, int(kForceStride));
  headroom_ = row_headroom(force_headroom(md_, 1 + die_count, die_count + dies_->face_terms(), comm_));
  force_terms_ = force_terms(md_, *dies_, *parts_, comm_);
  if (heat_) heat_ = std::make_unique<HeatTransfer>(md_, scene_, comm_);  // the capacities on the new reference
  results_ = collectively(
      comm_, [&] { return std::make_unique<ResultWriter>(opt_.case_dir, md_, scene_.prep_hash, results_->frames()); });
  v_old_.assign(st_.v.size(), 0.0);
  if (subcycles_) start_subcycles();  // a restart after updates (each particle's own step came with it)
  if (frequency_) frequency_ = collectively(comm_, [&] { return std::make_unique<HighestFrequency>(md_, comm_); });
}

namespace {

// Every rank's file from one rkprep run: the files of two preps of one scene (another --partitioner)
// passed each file's checks and crashed the first overlap exchange (MPI_ERR_TRUNCATE, no message).
void check_one_partition(const std::string& partition, const std::string& case_dir, const Comm& comm) {
  const std::uint64_t h = partition.empty() ? 0 : std::stoull(partition, nullptr, 16);
  const std::vector<double> all = comm.gather_all({double(h >> 32), double(h & 0xffffffffu)});  // (exact in doubles)
  int other = -1;
  for (int q = 1; q < comm.size() && other < 0; ++q)
    if (all[2 * std::size_t(q)] != all[0] || all[2 * std::size_t(q) + 1] != all[1]) other = q;
  comm.check(other < 0, subdomain_path(case_dir, std::max(other, 0)) + " was written by another rkprep run than " +
                            subdomain_path(case_dir, 0) + " (another partition of the part); re-run rkprep for the case");
}

}  // namespace

Simulation::Simulation(const SolveOptions& opt, const Comm& comm)
    : opt_(opt), comm_(comm), wall0_(comm.wtime()), baseline_mb_(process_memory_mb("VmRSS:")) {
  // baseline_mb_: the program and its libraries (MPI), before any data
  std::vector<Override> sets = opt.overrides;  // a restart's: the run's own --set values, then its own (io/run_scene.hpp)
  scene_ = collectively(comm, [&] {
    return opt.restart ? restart_scene(opt.case_dir, opt.overrides, sets)
                       : load_scene(opt.case_dir + "/scene.resolved.yaml", opt.overrides, Side::solve);
  });
  if (opt.restart && !sets.empty() && !opt.quiet && comm.rank() == 0) {
    std::fprintf(stderr, "rksolve: restart with");
    for (const Override& o : sets) std::fprintf(stderr, " --set %s=%s", o.path.c_str(), o.value.c_str());
    std::fprintf(stderr, "\n");
  }
  std::string stage_checkpoint;  // a stage: the previous case's checkpoint, and what its dies carry over
  DieCarry carry;
  if (!opt.from.empty())
    stage_ = begin_stage(opt.from, opt.case_dir, scene_, comm, stage_checkpoint, carry), staged_ = true;
  else if (opt.restart)
    staged_ = collectively(comm, [&] { return read_stage_link(opt.case_dir, stage_); });
  if (staged_) {
    apply_stage(stage_, scene_);
    t0_ = stage_.start, dwell_ = stage_.dwell;
  }
  std::string partition;
  md_ = collectively(comm, [&] {
    const Subdomain sub = read_subdomain(subdomain_path(opt.case_dir, comm.rank()), comm.rank(), comm.size(), scene_.prep_hash);
    partition = sub.partition_hash;
    return build_model(sub, scene_);
  });
  check_one_partition(partition, opt.case_dir, comm);
  comm.check(md_.dies.size() == scene_.dies.size(), "the subdomain files hold " + std::to_string(md_.dies.size()) +
                                                        " dies but the scene declares " +
                                                        std::to_string(scene_.dies.size()) + "; re-run rkprep");
  st_ = State::initial(md_, scene_.initial.velocity.data(), scene_.initial.velocity_gradient.data());
  for (std::size_t I = 0; I < md_.n; ++I)  // the bodies' own velocities
    if (md_.body[I] > 0)
      for (int i = 0; i < 3; ++i) st_.v[3 * I + i] = scene_.bodies[md_.body[I] - 1u].velocity[i];
  init_bulk_viscosity(md_, st_, scene_.bulk_viscosity);
  if (scene_.time.subcycling > 1)  // (or the checkpoint's)
    st_.particle_dt_half.assign(md_.n, 0.0), st_.cell_t_last.assign(md_.cells, 0.0);
  if (scene_.material.thermal()) {  // by the points' positions at t = 0
    st_.temperature.resize(md_.m);
    for (std::size_t g = 0; g < md_.m; ++g) st_.temperature[g] = scene_.initial.temperature_at(&md_.point_X[3 * g]);
  }
  // the plastic strain rate: for the flow stress of shear friction, and shown with a temperature
  bool rates = scene_.material.thermal();
  for (const Die& d : scene_.dies) rates = rates || d.shear_factor > 0;
  if (rates) st_.plastic_rate.assign(md_.m, 0.0);
  // the stretch at the uniform initial temperature T0, 1: a point that starts elsewhere (a temperature region)
  // has its thermal strain's jump in the first step's thermal work, so the balance holds the energy it starts with
  if (md_.thermal_strain()) st_.stretch_last.assign(md_.m, 1.0);
  if (scene_.damage.on()) st_.damage.assign(kDamageCriteria * md_.m, 0.0);
  std::int64_t crowded = -1;  // an F-bar cell with more points than the stress update's per-cell scratch holds
  for (std::size_t c = 0; md_.fbar && c < md_.cells && crowded < 0; ++c)
    if (std::size_t(md_.cell_points[c + 1] - md_.cell_points[c]) > kMaxCellPoints) crowded = std::int64_t(c);
  comm.check(crowded < 0, "cell " + std::to_string(crowded) + " of rank " + std::to_string(comm.rank()) + " in " +
                              subdomain_path(opt_.case_dir, comm.rank()) + " holds more than " +
                              std::to_string(kMaxCellPoints) +
                              " integration points, the most an F-bar cell may hold (rkprep makes at most 27); re-run rkprep");
  if (scene_.material.conducting())  // set by HeatTransfer::start or read from the checkpoint
    st_.particle_temperature.assign(md_.n, scene_.initial.temperature), st_.heat_pending.assign(md_.m, 0.0),
    st_.surface_heat.assign(md_.n, 0.0);
  compute_deformation_gradient(md_, st_);
  double dt0 = stable_time_step(md_, st_, scene_.time.cfl).dt;
  if (scene_.time.stable_step == "frequency") {  // (the mass scaling below then sized on it)
    frequency_ = collectively(comm, [&] { return std::make_unique<HighestFrequency>(md_, comm); });
    dt0 *= frequency_->step_ratio(md_, st_, comm);
    if (scene_.time.cfl > 1) {
      char text[300];
      std::snprintf(text, sizeof text, "time.cfl = %g with time.stable_step = frequency is past the stability limit "
                    "2 / omega_max: the run will grow unstable and stop; 0.9 is the default", scene_.time.cfl);
      start_warnings_.push_back(text);
      if (comm.rank() == 0) std::fprintf(stderr, "rksolve: warning: %s\n", text);
    }
  }
  comm.min(&dt0, 1);
  if (scene_.time.mass_scaling_dt > dt0) {  // quasi-static forming: scale the density up
    const double factor = std::pow(scene_.time.mass_scaling_dt / dt0, 2);
    scale_mass(md_, factor);
    dt0 *= std::sqrt(factor);
  }
  ebc_ = collectively(comm, [&] { return std::make_unique<EssentialBcs>(md_, scene_, comm); });
  ebc_->apply(md_, st_, 0.0, 0.0, 0.0, st_.v);  // initial velocities that meet the conditions' rates
  dies_ = std::make_unique<DieContact>(md_, scene_, md_.dies);
  parts_ = std::make_unique<PartContact>(md_, scene_, comm);
  if (!md_.dies.empty()) {  // the headroom of the dies' fixed-point sums: every rank's contact terms
    double terms = double(dies_->terms());
    comm.sum(&terms, 1);
    die_headroom_ = headroom_bits(std::int64_t(terms) + 1);
    fill_ = std::make_unique<DieFill>(md_, scene_, die_headroom_, comm);
  }
  clock_.dt_stable = dt0;  // the last unclipped global stable step: the stick force's step
  clock_.dt_penalty = dt0;  // and the smallest so far: the penalty stiffness
  clock_.kinetic0 = compute_energies(md_, st_, st_.v, comm).kinetic;
  if (opt.restart) {
    const std::string path = restart_checkpoint(opt.case_dir, comm);
    collectively(comm, [&] { return read_checkpoint(path, md_, st_, clock_, *dies_), 0; });
    if (st_.t > scene_.time.end * (1 + 1e-12)) {  // (the same on every rank: they restart from one step)
      char times[96];
      std::snprintf(times, sizeof times, "key 'time.end' = %g s is before the checkpoint's t = %g s", scene_.time.end, st_.t);
      throw Error(times + (" (" + path + "): a restart goes on to a later time.end"));
    }
  } else {
    collectively(comm, [&] { return remove_checkpoints(opt.case_dir, comm.rank()), 0; });
  }
  collectively(comm, [&] {
    if (comm.rank() != 0) return 0;
    write_run_scene(opt.case_dir, scene_, sets);  // (a restart's too: the next goes on with its end and intervals)
    // a run without --from or --restart is no stage: an earlier run's link would chain it to another case's frames
    if (opt.from.empty() && !opt.restart) std::filesystem::remove(opt.case_dir + "/" + kStageLinkFile);
    return 0;
  });
  if (!opt.from.empty()) {  // a stage: the previous case's final state, this stage's own records
    collectively(comm, [&] { return read_checkpoint(stage_checkpoint, md_, st_, clock_, *dies_, &carry), 0; });
    clock_.next_history = st_.t;  // a row at the stage's start
    clock_.next_output = st_.t;   // and a frame (the previous stage's grid left it without one where it ended off it)
    clock_.max_error = clock_.max_ke_ratio = clock_.max_ke_ratio_late = clock_.max_pressure_ratio = 0;
    clock_.frames = 0;
    // The kinetic energy the stage changes is work done on the part, so the balance goes on: another
    // mass scaling scales it (the masses are the same masses scaled), a dwell sets the part down.
    const double before = collectively(comm, [&] { return read_run_summary(opt.from + "/solve.json").mass_scaling; });
    double kinetic = 0;  // this rank's, at the stage's masses
    for (std::size_t I = 0; I < md_.n; ++I)
      for (int i = 0; i < 3 && md_.owned[I]; ++i) kinetic += 0.5 * md_.mass[I] * st_.v[3 * I + i] * st_.v[3 * I + i];
    const double previous = kinetic * (before / md_.mass_scaling);  // (the ratio first: 1 exactly for the same scaling)
    st_.external_work += (dwell_ ? 0.0 : kinetic) - previous;
    if (dwell_) {
      warn_if_moving(comm);
      std::fill(st_.v.begin(), st_.v.end(), 0.0);
    }
    collectively(comm, [&] { return comm.rank() == 0 ? (write_stage_link(opt.case_dir, stage_), 0) : 0; });
  }
  results_ = collectively(comm, [&] {
    return std::make_unique<ResultWriter>(opt.case_dir, md_, scene_.prep_hash, opt.restart ? clock_.frames : -1);
  });
  last_frame_ = [this] { write_frame(st_.v); };
  first_step_ = st_.step;
  const int die_count = int(md_.dies.size());
  exchange_.emplace(md_, int(kForceStride));
  if (scene_.time.subcycling > 1) start_subcycles();
  last_checkpoint_step_ = st_.step;
  headroom_ = row_headroom(force_headroom(md_, 1 + die_count, die_count + dies_->face_terms(), comm));
  force_terms_ = force_terms(md_, *dies_, *parts_, comm);
  v_old_.assign(st_.v.size(), 0.0);
  if (st_.reference_updates > 0) {  // a restart after updates: back onto the checkpoint's reference
    collectively(comm, [&] { return rebuild_on_reference(md_, st_, scene_, comm), 0; });
    rebind();
  }
  if (scene_.material.conducting()) {
    heat_ = collectively(comm, [&] { return std::make_unique<HeatTransfer>(md_, scene_, comm); });
    if (!opt.restart && !staged_) heat_->start(md_, st_, *dies_, comm);
  }
  history_ = std::make_unique<History>(opt.case_dir, scene_, md_, opt.restart ? st_.t : -1.0, comm);
  tracks_ = collectively(comm, [&] { return std::make_unique<PointTracks>(opt.case_dir, scene_, md_, opt.restart ? st_.t : -1.0, comm); });

  HealthScales scales;
  scales.dt0 = dt0;
  for (int d = 0; d < 3; ++d) scales.part_lo[d] = 1e300, scales.part_hi[d] = -1e300;
  for (std::size_t I = 0; I < md_.n; ++I)
    for (int d = 0; d < 3; ++d)
      scales.part_lo[d] = std::min(scales.part_lo[d], md_.X[3 * I + d]),
      scales.part_hi[d] = std::max(scales.part_hi[d], md_.X[3 * I + d]);
  comm.min(scales.part_lo, 3);
  comm.max(scales.part_hi, 3);
  scales.h_min = 1e300;  // the smallest particle spacing, the scale of the symmetry planes' check
  for (std::size_t I = 0; I < md_.n; ++I) scales.h_min = std::min(scales.h_min, md_.spacing0[I]);
  comm.min(&scales.h_min, 1);
  scales.v_start = fastest_speed(scene_, scales.part_lo, scales.part_hi);  // the fastest start or tool (m/s)
  health_ = std::make_unique<HealthChecks>(scene_, scales);
  // rho c_L v_max at the density the run uses (mass scaling raises a tool's starting pressure with it),
  // of the stiffest of the materials
  double impedance = 0;
  for (const Solid& s : md_.materials) impedance = std::max(impedance, std::sqrt(s.density * s.wave_modulus));
  pressure_bound_ = {impedance * scales.v_start, scene_.health.max_pressure_ratio};
  start_presses(scales.h_min);
  check_reach();

  last_checkpoint_wall_ = comm.wtime();
  setup_s_ = comm.wtime() - wall0_;
  const std::string first_die = scene_.dies.empty() ? "" : scene_.dies[0].name;
  progress_ = std::make_unique<Progress>(!opt.quiet && comm.rank() == 0, comm.size(), comm.wtime(), opt.progress_s, t0_,
                                         scene_.time.end, history_->columns(), first_die, st_);
  progress_->banner(opt.restart, setup_s_, md_.mass_scaling, scene_.time.subcycling);
  if (staged_ && !opt.restart && !opt.quiet && comm.rank() == 0) {
    int kept = 0;
    for (int k : stage_.continues) kept += k >= 0 ? 1 : 0;
    std::printf("rksolve: a stage from %s at t = %g s: %d dies going on, %d new%s\n", stage_.from.c_str(), t0_, kept,
                int(stage_.continues.size()) - kept, dwell_ ? "; a dwell: the temperature alone, at the thermal step" : "");
  }
  if (comm.rank() == 0)  // suspicious temperatures and costly settings before the run, not only in its report
    for (const std::string& w : scene_warnings(scene_)) std::fprintf(stderr, "rksolve: warning: %s\n", w.c_str());
  g_interrupted = 0;
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
}

// The dies driven by their press: their rams at rest at stroke 0 (or the checkpoint's), each heavy
// enough for the penalty contact: a ram of modeled mass M / force_factor against slaves of mass sum m
// in contact, k = s m / dt^2 each, is stable while M / force_factor > s sum m / 4; the slaves
// (particles and points) hold at most twice the part's mass, so M / force_factor >= s x the part's
// mass (mass-scaled) keeps a margin of 2. After a reference update the step grows past the one the
// stiffness keeps to (reference_updates.step_growth g), so there the springs take min(s g^2, 1) m / dt^2.
void Simulation::start_presses(double h_min) {
  std::size_t rams = 0;
  for (const Die& d : scene_.dies) rams += d.motion.driven() ? 1 : 0;
  if (rams == 0) return;
  presses_ = std::make_unique<Presses>(scene_, h_min, die_headroom_);
  double part_mass = 0;
  for (std::size_t I = 0; I < md_.n; ++I)
    if (md_.owned[I]) part_mass += md_.mass[I];
  comm_.sum(&part_mass, 1);
  for (const Die& d : scene_.dies) {
    const double s = scene_.penalty_scale_at_cfl(), g = scene_.reference_updates.step_growth;
    const double least = (scene_.reference_updates.strain > 0 ? std::max(s, std::min(s * g * g, 1.0)) : s) * part_mass * d.force_factor;
    if (!d.motion.driven() || d.motion.ram.mass >= least) continue;
    char text[300];
    std::snprintf(text, sizeof text, "die '%s': a ram_mass of %.4g kg is too light for the penalty contact against the part "
                  "(%.4g kg%s): give at least %.4g kg", d.name.c_str(), d.motion.ram.mass, part_mass * d.force_factor,
                  md_.mass_scaling > 1 ? " mass-scaled; or lower time.mass_scaling_dt" : "", least);
    throw Error(text);
  }
  if (opt_.restart)
    comm_.check(st_.rams.size() == rams, "the checkpoint holds no press state for this scene's rams; re-run from the start");
  else presses_->start(st_);
  presses_->place(st_, *dies_, false);
}

// A die whose whole travel over the run is shorter than its distance to the part along its motion
// (a crank stroke shorter than the gap, a die in the wrong place) cannot form it: an error when the
// part waits for it (at rest, no gravity, no other tool moving), a warning when something else may
// bring the part to it. The distance is bounded below by the boxes' gap along the motion,
// min over the part of X . d - max over the die of V . d, so no reachable die is refused.
void Simulation::check_reach() {
  const Scene& sc = scene_;
  int movers = int(sc.prescribed_faces.size());
  for (const Die& d : sc.dies) movers += d.motion.reach(sc.time.end) > 0 ? 1 : 0;
  bool part_moves = norm(sc.loads.gravity) > 0 || norm(sc.initial.velocity) > 0 || staged_;  // a stage's part may move
  for (double g : sc.initial.velocity_gradient) part_moves = part_moves || g != 0;
  for (std::size_t k = 0; k < sc.dies.size(); ++k) {
    const DieMotion& m = sc.dies[k].motion;
    const double reach = m.reach(sc.time.end);
    if (!(reach > 0) || std::isinf(reach)) continue;  // a die at rest waits for the part; a blow goes on
    double part = 1e300, die = -1e300;
    const double* d = m.direction.data();
    for (std::size_t I = 0; I < md_.n; ++I) part = std::min(part, md_.X[3 * I] * d[0] + md_.X[3 * I + 1] * d[1] + md_.X[3 * I + 2] * d[2]);
    comm_.min(&part, 1);
    const DieSurface& surface = md_.dies[k];
    for (std::size_t v = 0; v < surface.vertices.size() / 3; ++v) {
      const double* x = &surface.vertices[3 * v];
      die = std::max(die, x[0] * d[0] + x[1] * d[1] + x[2] * d[2]);
    }
    const double gap = part - die;
    if (gap <= reach * (1 + 1e-9)) continue;
    char text[400];
    std::snprintf(text, sizeof text, "die '%s' moves %.4g mm over the run but starts %.4g mm from the part along its motion: "
                  "it never reaches the part%s; lengthen its stroke or the run, or move it closer",
                  sc.dies[k].name.c_str(), 1e3 * reach, 1e3 * gap, part_moves || movers > 1 ? " unless something brings the part to it" : "");
    if (!part_moves && movers == 1) throw Error(text);
    start_warnings_.push_back(text);
    if (comm_.rank() == 0) std::fprintf(stderr, "rksolve: warning: %s\n", text);
  }
}

// solve.json (io/run_report.hpp) and the closing line
void Simulation::finish() {
  RunCounts counts;
  counts.wall0 = wall0_, counts.setup_s = setup_s_, counts.baseline_mb = baseline_mb_;
  counts.plastic_updates = plastic_updates_, counts.point_updates = point_updates_;
  counts.max_ebc_error = max_ebc_error_, counts.impact_pressure = pressure_bound_.impact;
  counts.max_penetration = max_penetration_, counts.h_min = health_->scales().h_min, counts.v_start = health_->scales().v_start;
  counts.frames = results_->frames();
  counts.first_step = first_step_;
  counts.start_warnings = start_warnings_;
  counts.warnings = run_warnings_;
  if (presses_) {
    counts.presses = presses_->outcome(st_, scene_.dies);
    for (std::size_t r = 0; r < counts.presses.size(); ++r)
      if (presses_->stalled(st_, r)) counts.warnings.push_back(counts.presses[r]);
  }
  const RunSummary s = write_run_report(opt_.case_dir, scene_, md_, st_, clock_, *dies_, *ebc_, timer_, counts, comm_);
  progress_->done(st_.step - first_step_, s.wall_s, s.ns_per_point_update, s.ns_per_particle_step, clock_.last_error);
}

}  // namespace

void solve_case(const SolveOptions& opt, const Comm& comm) {
  const auto lock = collectively(comm, [&] { return comm.rank() == 0 ? std::make_unique<CaseLock>(opt.case_dir) : nullptr; });
  Simulation simulation(opt, comm);
  simulation.run();
  simulation.finish();
}

}  // namespace rk
