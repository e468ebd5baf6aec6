#include "solver.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "boundary/essential_bc.hpp"
#include "bulk_viscosity.hpp"
#include "checkpoint.hpp"
#include "contact/die_contact.hpp"
#include "energy.hpp"
#include "error.hpp"
#include "internal_force.hpp"
#include "kinematics.hpp"
#include "model.hpp"
#include "output.hpp"
#include "overlap_exchange.hpp"
#include "phase_timer.hpp"
#include "process_memory.hpp"
#include "reference_update.hpp"
#include "state.hpp"
#include "stress_update.hpp"
#include "subdomain.hpp"
#include "time_step.hpp"

namespace rk {
namespace {

// Ctrl-C (SIGINT) or a job scheduler's SIGTERM: the run stops at the next step on every rank, after
// writing a checkpoint and a frame, so that --restart goes on from there.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void request_stop(int signal) { g_interrupted = signal; }

// Runs `fn` on every rank; an rk::Error on any rank becomes the same error on all ranks.
template <class Fn>
auto collectively(const Comm& comm, Fn fn) {
  std::string message;
  decltype(fn()) result{};
  try {
    result = fn();
  } catch (const Error& e) {
    message = e.what();
  }
  comm.check(message.empty(), message);
  return result;
}

// "particle 12 at (x, y, z) m": the current position (of the material, X_I + u^h(X_I), for an owned
// particle; else X_I + d_I), for messages the user can act on
std::string describe_particle(const Model& md, const State& st, std::int32_t I) {
  double u[3] = {st.u[3 * I], st.u[3 * I + 1], st.u[3 * I + 2]};
  if (md.material_offsets[I + 1] > md.material_offsets[I]) material_displacement(md, st, std::size_t(I), u);
  std::ostringstream s;
  s << "particle " << md.global_id[I] << " at (" << md.X[3 * I] + u[0] << ", " << md.X[3 * I + 1] + u[1] << ", "
    << md.X[3 * I + 2] + u[2] << ") m";
  return s.str();
}

std::vector<std::string> history_columns(const Scene& scene) {
  std::vector<std::string> c{"time",         "dt",          "kinetic",      "internal",      "plastic_work",
                             "external_work", "contact_work", "energy_error", "friction_work", "contacts",
                             "point_contacts", "max_penetration", "kinetic_internal_ratio", "volume_change", "ebc_error", "update_work",
                             "spring_energy", "symmetry_depth", "viscous_work"};
  for (const auto& w : scene.rigid_walls) c.push_back(w.name + ".force");
  for (const auto& d : scene.dies)
    for (const char* q : {".stroke", ".force", ".fx", ".fy", ".fz", ".work"}) c.push_back(d.name + q);
  for (const auto& f : scene.fixed_faces)
    for (const char* q : {".fx", ".fy", ".fz"}) c.push_back(f.name + q);
  for (const auto& f : scene.prescribed_faces)
    for (const char* q : {".stroke", ".fx", ".fy", ".fz"}) c.push_back(f.name + q);
  return c;
}

}  // namespace

void solve_case(const SolveOptions& opt, const Comm& comm) {
  const double wall0 = comm.wtime();
  const double baseline_mb = process_memory_mb("VmRSS:");  // the program and its libraries (MPI), before any data
  const Scene scene = collectively(
      comm, [&] { return load_scene(opt.case_dir + "/scene.resolved.yaml", opt.overrides, Side::solve); });
  Model md = collectively(comm, [&] {
    return build_model(read_subdomain(subdomain_path(opt.case_dir, comm.rank()), comm.rank(), comm.size(),
                                      scene.prep_hash),
                       scene);
  });
  comm.check(md.dies.size() == scene.dies.size(), "the subdomain files hold " + std::to_string(md.dies.size()) +
                                                      " dies but the scene declares " + std::to_string(scene.dies.size()) +
                                                      "; re-run rkprep");
  State st = State::initial(md, scene.initial.velocity.data(), scene.initial.velocity_gradient.data());
  init_bulk_viscosity(md, st, scene.bulk_viscosity);
  compute_deformation_gradient(md, st);
  double dt0 = stable_time_step(md, st, scene.time.cfl).dt;
  comm.min(&dt0, 1);
  if (scene.time.mass_scaling_dt > dt0) {  // quasi-static forming: scale the density up
    const double factor = std::pow(scene.time.mass_scaling_dt / dt0, 2);
    scale_mass(md, factor);
    dt0 *= std::sqrt(factor);
  }
  auto ebc = collectively(comm, [&] { return std::make_unique<EssentialBcs>(md, scene, comm); });
  ebc->apply(md, st, 0.0, 0.0, 0.0, st.v);  // initial velocities that meet the conditions' rates
  const bool has_gravity = norm(scene.loads.gravity) > 0;
  auto dies = std::make_unique<DieContact>(md, scene, md.dies);
  RunClock clock;
  clock.dt_stable = dt0;  // the last unclipped global stable step: sets the penalty stiffness
  clock.kinetic0 = compute_energies(md, st, st.v, comm).kinetic;
  if (opt.restart) {
    const std::string path = restart_checkpoint(opt.case_dir, comm);
    collectively(comm, [&] { return read_checkpoint(path, md, st, clock, dies->totals()), 0; });
  } else {
    collectively(comm, [&] { return remove_checkpoints(opt.case_dir, comm.rank()), 0; });
  }
  auto results = collectively(comm, [&] {
    return std::make_unique<ResultWriter>(opt.case_dir, md, scene.prep_hash, opt.restart ? clock.frames : -1);
  });
  std::unique_ptr<HistoryWriter> history;
  const std::vector<std::string> columns = history_columns(scene);
  if (comm.rank() == 0)
    history = std::make_unique<HistoryWriter>(opt.case_dir + "/history.csv", columns, opt.restart ? st.t : -1.0);
  const std::int64_t first_step = st.step;
  // Output is collective; a failure on any rank (disk full, unwritable directory) stops every rank.
  auto write_frame = [&](const std::vector<double>& velocity) {
    collectively(comm, [&] { return results->write_frame(md, st, velocity, comm), 0; });
  };
  std::optional<OverlapExchange> exchange;
  exchange.emplace(md, 3);
  const int die_count = int(md.dies.size());
  int headroom = force_headroom(md, 1 + die_count, die_count, comm);  // of the fixed-point force sums
  std::vector<double> v_old(st.v.size());
  // A reference update changes the rank's local particles: what is sized by them is rebuilt.
  auto rebind = [&] {
    ebc = collectively(comm, [&] { return std::make_unique<EssentialBcs>(md, scene, comm); });
    const std::vector<DieTotals> totals = dies->totals();
    dies = std::make_unique<DieContact>(md, scene, md.dies);
    dies->totals() = totals;
    exchange.emplace(md, 3);
    headroom = force_headroom(md, 1 + die_count, die_count, comm);
    results = collectively(comm, [&] { return std::make_unique<ResultWriter>(opt.case_dir, md, scene.prep_hash, results->frames()); });
    v_old.assign(st.v.size(), 0.0);
  };
  if (st.reference_updates > 0) {  // a restart after updates: back onto the checkpoint's reference
    collectively(comm, [&] { return rebuild_on_reference(md, st, scene, comm), 0; });
    rebind();
  }
  const double update_strain = scene.reference_updates.strain;
  bool update_due = false;
  std::vector<double> row(columns.size(), 0.0);
  // Global sums for a history row, laid out as: the scalars below, one force per rigid wall, then
  // (contacts, fx, fy, fz, press work) per die, then (fx, fy, fz) per fixed or prescribed face.
  enum { kContacts, kPointContacts, kSprings, kFriction, kContactWork, kVolume, kEbcWork, kUpdateWork, kViscousWork, kScalars };
  std::vector<double> sums(kScalars + scene.rigid_walls.size() + 5 * scene.dies.size() + ebc->reactions().size());
  double max_ebc_error = 0;
  double part_lo[3] = {1e300, 1e300, 1e300}, part_hi[3] = {-1e300, -1e300, -1e300};  // the part's initial box
  for (std::size_t I = 0; I < md.n; ++I)
    for (int d = 0; d < 3; ++d) part_lo[d] = std::min(part_lo[d], md.X[3 * I + d]), part_hi[d] = std::max(part_hi[d], md.X[3 * I + d]);
  comm.min(part_lo, 3);
  comm.max(part_hi, 3);
  double h_min = 1e300;  // the smallest particle spacing, the scale of the symmetry planes' health check
  for (std::size_t I = 0; I < md.n; ++I) h_min = std::min(h_min, md.spacing0[I]);
  comm.min(&h_min, 1);
  const double v_start = fastest_speed(scene, part_lo, part_hi);  // the fastest start or tool (m/s)
  // rho c_L v_max at the density the run uses: mass scaling raises a tool's starting pressure with it
  const PressureBound pressure_bound{std::sqrt(md.density * md.wave_modulus) * v_start,
                                     scene.health.max_pressure_ratio};
  double volume0 = 0;  // sum of the points' reference volumes (each point lives on one rank)
  for (std::size_t g = 0; g < md.m; ++g) volume0 += md.weight[g];
  comm.sum(&volume0, 1);

  const double t_end = scene.time.end, out_dt = scene.time.output_interval;
  const double hist_dt = t_end / 500;
  double& next_output = clock.next_output;
  double& next_history = clock.next_history;
  double& dt_stable = clock.dt_stable;
  double& last_error = clock.last_error;
  double& max_ke_ratio = clock.max_ke_ratio;
  const double kinetic0 = clock.kinetic0;
  PhaseTimer timer;
  double plastic_updates = 0, point_updates = 0;  // this run's stress updates, and those that were plastic
  bool checkpoint_due = false;
  double last_checkpoint_wall = comm.wtime();
  const double setup_s = comm.wtime() - wall0;
  double last_progress = comm.wtime();
  // Under mpirun a rank's stdout is a pseudo-terminal even when mpirun's output goes to a file, so
  // the updating line is kept for runs started without a launcher; launched runs print plain lines.
  const bool launched = std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_RANK") || std::getenv("PMIX_RANK");
  const bool terminal = !launched && ::isatty(::fileno(stdout)) != 0;
  bool progress_shown = false;  // an updating line is on the terminal: end it before other output
  std::int64_t progress_step = st.step;
  double progress_t = st.t;
  // the progress line's press: the first die's stroke column (its force follows it), -1 without dies
  const auto stroke_column = scene.dies.empty() ? columns.end()
                                                : std::find(columns.begin(), columns.end(), scene.dies[0].name + ".stroke");
  const std::ptrdiff_t die_column = stroke_column == columns.end() ? -1 : stroke_column - columns.begin();
  if (!opt.quiet && comm.rank() == 0) {
    if (opt.restart)
      std::printf("rksolve: %d ranks, restarted from the checkpoint of step %lld, t = %g s (setup %.2f s), running to "
                  "t = %g s\n", comm.size(), static_cast<long long>(st.step), st.t, setup_s, t_end);
    else
      std::printf("rksolve: %d ranks, setup %.2f s, mass scaling %.3g, running to t = %g s\n", comm.size(), setup_s,
                  md.mass_scaling, t_end);
  }
  g_interrupted = 0;
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  bool stop_requested = false;  // a rank was interrupted: checkpoint, frame, then stop (every rank)

  for (;;) {
    timer.start();
    const bool last = st.t >= t_end * (1 - 1e-12);
    if (update_due) {  // the current configuration becomes the reference
      const Projection project = [&](std::size_t I, double* x) { ebc->project(md, I, st.t, x); };
      collectively(comm, [&] { return update_reference(md, st, scene, comm, project), 0; });
      rebind();
      update_due = false;
      timer.stop(kReference);
    }
    const auto every = scene.output.checkpoint_steps;
    if ((every > 0 && st.step % every == 0 && st.step > first_step) || last || checkpoint_due) {  // t^n, v^{n-1/2}
      checkpoint_due = false;
      last_checkpoint_wall = comm.wtime();
      clock.frames = results->frames();
      collectively(comm, [&] { return write_checkpoint(opt.case_dir, md, st, clock, dies->totals()), 0; });
      timer.stop(kOutput);
    }
    if (stop_requested) {
      compute_deformation_gradient(md, st);  // the frame's stresses are this state's (t^n)
      update_bulk_viscosity(md, st, scene.bulk_viscosity);
      update_stress(md, st, pressure_bound);
      write_frame(st.v);
      std::ostringstream why;
      why << "interrupted at step " << st.step << ", t = " << st.t
          << " s: checkpoint and last frame written; `rksolve " << opt.case_dir << " --restart` goes on from here";
      throw Error(why.str());
    }
    compute_deformation_gradient(md, st);
    timer.stop(kDeformation);
    update_bulk_viscosity(md, st, scene.bulk_viscosity);
    const StressHealth health = update_stress(md, st, pressure_bound);
    plastic_updates += double(health.plastic);
    point_updates += double(md.m);
    timer.stop(kStress);
    const double contact_bound = dies->compute(md, st, st.t, dt_stable);
    timer.stop(kUpdate);

    double bound = contact_bound;
    for (std::size_t g = 0; g < md.m; ++g) bound = std::max(bound, st.force_bound[g]);
    const bool healthy = health.ok && std::isfinite(bound);
    const StableStep stable = stable_time_step(md, st, scene.time.cfl);
    // rank 0's clock decides whether a wall-clock checkpoint is due (written at the next step's top)
    const bool clock_due = comm.rank() == 0 && scene.output.checkpoint_minutes > 0 &&
                           comm.wtime() - last_checkpoint_wall >= 60 * scene.output.checkpoint_minutes;
    double red[8] = {-stable.dt, bound, healthy ? 0.0 : 1.0, clock_due ? 1.0 : 0.0,
                     update_strain > 0 ? largest_strain_since_update(md, st) : 0.0, dies->symmetry_depth() / h_min,
                     health.pressure_ratio, g_interrupted ? 1.0 : 0.0};
    comm.max(red, 8);
    clock.max_pressure_ratio = std::max(clock.max_pressure_ratio, red[6]);
    stop_requested = red[7] > 0;
    checkpoint_due = red[3] > 0 || stop_requested;
    update_due = update_strain > 0 && red[4] > update_strain;
    timer.stop(kTimeStep);
    if (-red[0] < scene.health.min_dt_ratio * dt0) {  // a cell has collapsed: the run would never end
      write_frame(st.v);
      std::ostringstream why;
      why << "the stable time step collapsed to " << stable.dt << " s (" << stable.dt / dt0
          << " of the initial step) at step " << st.step << ", t = " << st.t << " s, in the cell of "
          << describe_particle(md, st, md.cell_nodes[md.cell_node_offsets[stable.cell]])
          << " (last frame written); refine the spacing there";
      comm.check(stable.dt > -red[0], why.str());
    }
    if (red[5] > scene.health.max_symmetry_depth) {  // the material broke through a symmetry plane
      write_frame(st.v);
      const std::int32_t I = dies->deepest_particle(md);
      std::ostringstream why;
      if (I >= 0)
        why << "the material near " << describe_particle(md, st, I) << " is " << dies->symmetry_depth()
            << " m past a symmetry plane (health.max_symmetry_depth = " << scene.health.max_symmetry_depth
            << " spacings) at step " << st.step << ", t = " << st.t
            << " s (last frame written); the state is not physical: refine the spacing or reduce time.cfl";
      comm.check(I < 0 || dies->symmetry_depth() / h_min <= scene.health.max_symmetry_depth, why.str());
    }
    if (red[2] > 0) {  // a rank is unhealthy: show the user the state, then stop every rank
      std::ostringstream why;
      if (health.pressure_stop)
        why << "rank " << comm.rank() << ": the pressure near " << describe_particle(md, st, md.nbr[md.nbr_offsets[health.point]])
            << " is " << health.pressure << " Pa, " << health.pressure_ratio << " times rho0 c_L v_max + sigma_y = "
            << std::abs(health.pressure) / health.pressure_ratio << " Pa there (health.max_pressure_ratio = "
            << scene.health.max_pressure_ratio << ", v_max the fastest start or tool), at step " << st.step << ", t = " << st.t
            << " s: the state is not physical; refine the spacing or reduce time.cfl";
      else if (!health.ok)
        why << "rank " << comm.rank() << ": det F = " << health.J << " at step " << st.step << ", t = " << st.t
            << " s, near " << describe_particle(md, st, md.nbr[md.nbr_offsets[health.point]])
            << (health.J > 0 ? " (the material's volume ratio; outside (0.5, 2) no solid metal is, the state is not physical)"
                             : "");
      else
        why << "rank " << comm.rank() << ": non-finite forces at step " << st.step << ", t = " << st.t << " s";
      write_frame(st.v);
      comm.check(healthy, why.str() + " (last frame written)");
    }

    double dt = -red[0];
    dt_stable = dt;
    if (!last) {
      dt = std::min(dt, t_end - st.t);
      if (next_output - st.t > 1e-9 * out_dt) dt = std::min(dt, next_output - st.t);
    }
    const double dt_avg = st.step == 0 ? 0.5 * dt : 0.5 * (st.dt_half + dt);
    const FixedScale scale = FixedScale::for_bound(red[1], headroom);
    clear_internal_force(st);
    add_internal_force(md, st, scale, md.boundary_points);
    dies->add_to(md, st, scale);  // die contact forces of the owned particles and points, once over all ranks
    timer.stop(kInternalForce);
    exchange->start(st.partial);  // the overlap particles' partials travel ...
    timer.stop(kExchange);
    add_internal_force(md, st, scale, md.interior_points);  // ... while the interior is computed
    timer.stop(kInternalForce);
    exchange->finish(st.partial);
    timer.stop(kExchange);

    std::copy(st.v.begin(), st.v.end(), v_old.begin());
    const double* g = scene.loads.gravity.data();
    for (std::size_t I = 0; I < md.n; ++I)
      for (int i = 0; i < 3; ++i) {
        st.force[3 * I + i] = scale.real(st.partial[3 * I + i]);
        st.v[3 * I + i] += dt_avg * (g[i] - st.force[3 * I + i] / md.mass[I]);
      }
    ebc->apply(md, st, st.t + dt, dt, dt_avg, v_old);
    dies->account(md, st, v_old, dt_avg, st.t);
    if (has_gravity)  // work of the body force on the owned particles
      for (std::size_t I = 0; I < md.n; ++I)
        if (md.owned[I])
          for (int i = 0; i < 3; ++i) st.external_work += dt_avg * md.mass[I] * g[i] * 0.5 * (v_old[3 * I + i] + st.v[3 * I + i]);
    timer.stop(kUpdate);

    if (last || st.t >= next_history - 1e-9 * hist_dt) {  // history row at t^n
      Energies e = compute_energies(md, st, v_old, comm);
      const std::size_t walls = scene.rigid_walls.size(), die0 = kScalars + walls;
      std::fill(sums.begin(), sums.end(), 0.0);
      sums[kEbcWork] = ebc->step_work();
      sums[kUpdateWork] = st.update_work;
      sums[kViscousWork] = st.viscous_work;
      for (std::size_t g = 0; g < md.m; ++g) sums[kVolume] += md.weight[g] * st.total_J(g);
      for (std::size_t w = 0; w < walls; ++w) sums[kScalars + w] = dies->wall_force(w);
      double pen = 0;
      for (std::size_t d = 0; d < dies->totals().size(); ++d) {  // the dies, the rigid walls, then the symmetry planes
        const DieTotals& t = dies->totals()[d];
        sums[kSprings] += t.spring_energy, sums[kFriction] += t.friction_work, sums[kContactWork] += t.contact_work;
        if (d >= dies->size() + walls) continue;
        sums[kContacts] += double(t.contacts);
        sums[kPointContacts] += double(t.point_contacts);
        pen = std::max(pen, t.max_penetration);
        if (d >= dies->size()) continue;
        double* out = &sums[die0 + 5 * d];
        out[0] = double(t.contacts), out[1] = t.force[0], out[2] = t.force[1], out[3] = t.force[2], out[4] = t.press_work;
      }
      const std::size_t face0 = die0 + 5 * dies->size();
      std::copy(ebc->reactions().begin(), ebc->reactions().end(), sums.begin() + std::ptrdiff_t(face0));
      comm.sum(sums.data(), int(sums.size()));
      double worst[3] = {pen, ebc->max_error(md, st, st.t), dies->symmetry_depth()};
      comm.max(worst, 3);
      pen = worst[0];
      max_ebc_error = std::max(max_ebc_error, worst[1]);
      // The balance of the part (docs/scene.md, "Energy"): KE + internal = KE0 + W_ext + W_contact, with
      // W_contact the work of the contact forces on the material they hold. The penalty springs'
      // energy k d^2 / 2 is part of that work already (the dies' work less the springs' and friction's
      // share), so it is not counted again; it is reported in its own column.
      e.contact = sums[kContactWork];
      e.external -= 0.5 * sums[kEbcWork];
      Energies balance = e;  // the kinetic energy reference updates smoothed away is not an error
      balance.external += sums[kUpdateWork];
      last_error = energy_error(balance, kinetic0);
      // past the start-up: the first 100 steps, and for a part that starts at rest (its energy scale
      // grows from 0 with the tools' work) the first 10 % of the run; a die's first contacts take a
      // dozen steps, an unstable mode hundreds to thousands (the beam's at CFL 1.2, about 500)
      const bool started = st.step >= 100 && (kinetic0 > 0 || st.t > 0.1 * t_end);
      if (started || last) clock.max_error = std::max(clock.max_error, last_error);
      const double ratio = e.internal > 0 ? e.kinetic / e.internal : 0.0;
      if (st.t > 0.05 * t_end) max_ke_ratio = std::max(max_ke_ratio, ratio);
      std::size_t c = 0;
      for (double v : {st.t, dt, e.kinetic, e.internal, e.plastic, e.external, e.contact, last_error, sums[kFriction],
                       sums[kContacts], sums[kPointContacts], pen, ratio, sums[kVolume] / volume0 - 1, worst[1], sums[kUpdateWork],
                       sums[kSprings], worst[2], sums[kViscousWork]})
        row[c++] = v;
      for (std::size_t w = 0; w < walls; ++w) row[c++] = sums[kScalars + w];
      for (std::size_t d = 0; d < dies->size(); ++d) {
        const Die& die = dies->die(d);
        const double* f = &sums[die0 + 5 * d + 1];
        row[c++] = die.motion.stroke(st.t);
        row[c++] = die.force_factor * (f[0] * die.motion.direction[0] + f[1] * die.motion.direction[1] +
                                       f[2] * die.motion.direction[2]);
        row[c++] = f[0], row[c++] = f[1], row[c++] = f[2];
        row[c++] = f[3];
      }
      for (std::size_t f = 0; f < scene.fixed_faces.size() + scene.prescribed_faces.size(); ++f) {
        if (f >= scene.fixed_faces.size()) row[c++] = scene.prescribed_faces[f - scene.fixed_faces.size()].motion.stroke(st.t);
        for (int i = 0; i < 3; ++i) row[c++] = sums[face0 + 3 * f + i];
      }
      collectively(comm, [&] { return history ? (history->write(row), 0) : 0; });  // a full disk stops all ranks
      next_history += hist_dt;
      if (dies->size() > 0) {  // a particle that has left the tools' box: the run went wrong
        double lo[3], hi[3];
        dies->box(part_lo, part_hi, st.t, lo, hi);
        std::size_t out = md.n;
        for (std::size_t I = 0; I < md.n && out == md.n; ++I) {
          if (!md.owned[I]) continue;
          double uh[3];  // where the material at the particle is (the dies hold u^h(X_I), not d_I)
          material_displacement(md, st, I, uh);
          for (int d = 0; d < 3; ++d)
            if (!(md.X[3 * I + d] + uh[d] >= lo[d] && md.X[3 * I + d] + uh[d] <= hi[d])) out = I;
        }
        double escaped = out < md.n ? 1.0 : 0.0;
        comm.max(&escaped, 1);
        if (escaped > 0) {
          write_frame(st.v);
          std::ostringstream why;
          if (out < md.n)
            why << describe_particle(md, st, std::int32_t(out)) << " has left the box of the part and the dies ("
                << lo[0] << ", " << lo[1] << ", " << lo[2] << ") - (" << hi[0] << ", " << hi[1] << ", " << hi[2]
                << ") m at step " << st.step << ", t = " << st.t << " s (last frame written)";
          comm.check(out == md.n, why.str());
        }
      }
      // Runaway check; skipped in the start-up (started), where the energies are still tiny and the
      // first-order work of freshly engaged contacts dominates their ratio.
      if (last_error > scene.health.max_energy_error && started) {
        write_frame(st.v);
        // Where the energy grows: an unstable mode of the discretization moves the coefficients in a
        // pattern the field does not carry, so it shows as |v_I - v^h(X_I)|, largest at the mode.
        double worst = -1;
        std::int32_t where = -1;
        for (std::size_t I = 0; I < md.n; ++I) {
          if (!md.owned[I]) continue;
          double vh[3], d2 = 0;
          material_velocity(md, st.v, I, vh);
          for (int i = 0; i < 3; ++i) d2 += (st.v[3 * I + i] - vh[i]) * (st.v[3 * I + i] - vh[i]);
          if (d2 > worst) worst = d2, where = std::int32_t(I);
        }
        double largest = worst;
        comm.max(&largest, 1);
        std::ostringstream why;
        why << "energy error " << last_error << " exceeds health.max_energy_error = " << scene.health.max_energy_error
            << " at step " << st.step << ", t = " << st.t << " s (last frame written)";
        // a mode the field does not carry, faster than anything that started the run: unstable
        const bool mode = std::sqrt(std::max(largest, 0.0)) > 0.5 * v_start;
        if (where >= 0 && mode)
          why << "; the velocity the field does not carry is largest at " << describe_particle(md, st, where) << " ("
              << std::sqrt(std::max(worst, 0.0)) << " m/s): an unstable mode there; reduce time.cfl";
        else if (where >= 0)
          why << "; the field carries the particles' velocities (no unstable mode: at most "
              << std::sqrt(std::max(largest, 0.0)) << " m/s against the start's " << v_start
              << " m/s): a start too sudden (a die from rest to full speed: ramp it up with motion.curve), a contact "
                 "too coarse, or a bound below the method's error (health.max_energy_error)";
        comm.check(where < 0 || worst < largest, why.str());
        comm.check(false, why.str());
      }
    }
    if (last || st.t >= next_output - 1e-9 * out_dt) {  // frame at t^n with vbar
      for (std::size_t k = 0; k < v_old.size(); ++k) v_old[k] = 0.5 * (v_old[k] + st.v[k]);
      write_frame(v_old);
      next_output += out_dt;
      timer.stop(kOutput);
    }
    if (last) break;

    for (std::size_t k = 0; k < st.u.size(); ++k) st.u[k] += dt * st.v[k];
    st.t += dt;
    st.dt_half = dt;
    ++st.step;
    timer.stop(kUpdate);
    if (!opt.quiet && comm.rank() == 0 && comm.wtime() - last_progress > (terminal ? 2.0 : 10.0)) {
      const double now = comm.wtime(), rate = double(st.step - progress_step) / (now - last_progress);
      // the ETA from the last interval's pace (simulated seconds per wall second), not the run's average:
      // in forming the step keeps shrinking, and the average promised about half the time it took
      const double pace = (st.t - progress_t) / (now - last_progress);
      const double eta = pace > 0 ? (t_end - st.t) / pace : 0.0;
      last_progress = now;
      progress_step = st.step;
      progress_t = st.t;
      char press[96] = "";  // the first die's stroke and force, from the last history row
      if (die_column >= 0)
        std::snprintf(press, sizeof press, "  %s %.4g mm, %.4g kN", columns[std::size_t(die_column)].c_str(),
                      1e3 * row[std::size_t(die_column)], 1e-3 * row[std::size_t(die_column) + 1]);
      // a terminal gets one updating line; a pipe or a log gets a plain line every 10 s
      std::printf("%srksolve: t = %.4g s (%5.1f %%)  step %lld  %.0f steps/s  dt = %.3g s%s  energy error %.2e  ETA %.0f s%s",
                  terminal ? "\r" : "", st.t, 100 * st.t / t_end, static_cast<long long>(st.step), rate, dt, press,
                  last_error, eta, terminal ? "   " : "\n");
      std::fflush(stdout);
      progress_shown = terminal;
    }
  }

  // solve.json: totals and per-phase times (min/max over ranks)
  const double wall = comm.wtime() - wall0;
  double counts[6] = {0, double(md.m), double(md.nbr.size()), plastic_updates, point_updates, st.viscous_work};
  for (std::size_t I = 0; I < md.n; ++I) counts[0] += md.owned[I];
  comm.sum(counts, 6);
  std::array<double, kPhaseCount> lo = timer.seconds, hi = timer.seconds;
  comm.min(lo.data(), kPhaseCount);
  comm.max(hi.data(), kPhaseCount);
  // memory: the largest rank's peak, and per integration point (with its share of the particles,
  // neighbours and shape functions) the data above the program's own baseline, summed over ranks:
  // at the peak (setup temporaries included) and resident at the end (what the time loop holds)
  const double peak_mb = process_memory_mb("VmHWM:");
  double mem_max = peak_mb, mem_sum[2] = {peak_mb - baseline_mb, process_memory_mb("VmRSS:") - baseline_mb};
  comm.max(&mem_max, 1);
  comm.sum(mem_sum, 2);
  const double bytes_per_mb_point = 1048576.0 / std::max(counts[1], 1.0);
  // Suspicious but legal: a die that never touched the part (another unit, a wrong place, a motion
  // away from the part) leaves a run with no forming in it. Its work over the run (checkpointed) is 0.
  std::vector<double> touched(dies->size());
  for (std::size_t d = 0; d < dies->size(); ++d) {
    const DieTotals& t = dies->totals()[d];
    touched[d] = std::abs(t.press_work) + std::abs(t.contact_work) + std::abs(t.friction_work);
  }
  comm.sum(touched.data(), int(touched.size()));
  std::vector<std::string> warnings;
  for (std::size_t d = 0; d < dies->size(); ++d)
    if (touched[d] == 0)
      warnings.push_back("die '" + scene.dies[d].name + "' never touched the part in this run: check its CAD unit (dies[" +
                         std::to_string(d) + "].unit), its position and its motion's direction");
  if (comm.rank() == 0)
    for (const auto& w : warnings) std::fprintf(stderr, "rksolve: warning: %s\n", w.c_str());
  if (comm.rank() == 0) {
    nlohmann::json phases = nlohmann::json::object();
    for (int p = 0; p < kPhaseCount; ++p) phases[kPhaseNames[p]] = {{"min_s", lo[p]}, {"max_s", hi[p]}};
    const double loop_s = wall - setup_s;
    nlohmann::json j = {{"steps", st.step},
                        {"time", st.t},
                        {"wall_s", wall},
                        {"setup_s", setup_s},
                        {"ranks", comm.size()},
                        {"particles", std::int64_t(counts[0])},
                        {"integration_points", std::int64_t(counts[1])},
                        {"neighbours_per_point", counts[2] / std::max(counts[1], 1.0)},  // at the end
                        {"point_updates_per_s", loop_s > 0 ? counts[1] * double(st.step) / loop_s : 0.0},
                        {"ns_per_point_update", st.step > 0 ? 1e9 * loop_s * comm.size() / (counts[1] * double(st.step)) : 0.0},
                        {"plastic_fraction", counts[3] / std::max(counts[4], 1.0)},
                        {"energy_error", last_error},
                        {"max_energy_error", clock.max_error},
                        {"max_pressure_ratio", clock.max_pressure_ratio},
                        {"impact_pressure_pa", pressure_bound.impact},
                        {"ebc_method", scene.discretization.ebc_method},
                        {"constraints", ebc->constraints()},
                        {"max_ebc_error_m", max_ebc_error},
                        {"initial_kinetic_energy", kinetic0},
                        {"viscous_work", counts[5]},
                        {"mass_scaling", md.mass_scaling},
                        {"max_kinetic_internal_ratio", max_ke_ratio},
                        {"reference_updates", st.reference_updates},
                        {"frames", results->frames()},
                        {"peak_memory_mb_max_rank", mem_max},
                        {"peak_bytes_per_point", mem_sum[0] * bytes_per_mb_point},
                        {"resident_bytes_per_point", mem_sum[1] * bytes_per_mb_point},
                        {"phases", phases},
                        {"warnings", warnings}};
    std::ofstream(opt.case_dir + "/solve.json") << j.dump(2) << "\n";
    if (!opt.quiet && progress_shown) std::printf("\n");
    if (!opt.quiet)
      std::printf("rksolve: done, %lld steps, %.2f s wall (%.0f ns per point update), energy error %.2e\n",
                  static_cast<long long>(st.step), wall, j["ns_per_point_update"].get<double>(), last_error);
  }
}

}  // namespace rk
