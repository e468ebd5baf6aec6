#include "solver.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "boundary/symmetry.hpp"
#include "contact/rigid_wall.hpp"
#include "energy.hpp"
#include "error.hpp"
#include "internal_force.hpp"
#include "kinematics.hpp"
#include "model.hpp"
#include "output.hpp"
#include "overlap_exchange.hpp"
#include "phase_timer.hpp"
#include "state.hpp"
#include "stress_update.hpp"
#include "subdomain.hpp"
#include "time_step.hpp"

namespace rk {
namespace {

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

double peak_memory_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0;
}

std::string describe_point(const Model& md, const State& st, std::size_t g) {
  // the point's nearest particle, for a message the user can act on
  std::int32_t I = md.nbr[md.nbr_offsets[g]];
  std::ostringstream s;
  s << "near particle " << md.global_id[I] << " at (" << md.X[3 * I] + st.u[3 * I] << ", "
    << md.X[3 * I + 1] + st.u[3 * I + 1] << ", " << md.X[3 * I + 2] + st.u[3 * I + 2] << ") m";
  return s.str();
}

}  // namespace

void solve_case(const SolveOptions& opt, const Comm& comm) {
  const double wall0 = comm.wtime();
  const Scene scene = collectively(
      comm, [&] { return load_scene(opt.case_dir + "/scene.resolved.yaml", opt.overrides, Side::solve); });
  const Model md = collectively(comm, [&] {
    return build_model(read_subdomain(subdomain_path(opt.case_dir, comm.rank()), comm.rank(), comm.size(),
                                      scene.prep_hash),
                       scene);
  });
  auto results = collectively(comm, [&] { return std::make_unique<ResultWriter>(opt.case_dir, md); });
  std::unique_ptr<HistoryWriter> history;
  std::vector<std::string> wall_names;
  for (const auto& w : scene.rigid_walls) wall_names.push_back(w.name);
  if (comm.rank() == 0) history = std::make_unique<HistoryWriter>(opt.case_dir + "/history.csv", wall_names);

  State st = State::initial(md, scene.initial.velocity.data());
  apply_symmetry(md, st);
  OverlapExchange exchange(md, 3);
  std::vector<double> v_old(st.v.size());
  HistoryRow row{};
  row.wall_force.assign(scene.rigid_walls.size(), 0.0);
  std::vector<double> wall_force(scene.rigid_walls.size(), 0.0);

  const double t_end = scene.time.end, out_dt = scene.time.output_interval;
  const double hist_dt = t_end / 500;
  double next_output = 0, next_history = 0;
  const double kinetic0 = compute_energies(md, st, st.v, comm).kinetic;
  double last_error = 0;
  PhaseTimer timer;
  const double setup_s = comm.wtime() - wall0;
  double last_progress = comm.wtime();
  if (!opt.quiet && comm.rank() == 0)
    std::printf("rksolve: %d ranks, setup %.2f s, running to t = %g s\n", comm.size(), setup_s, t_end);

  for (;;) {
    timer.start();
    compute_deformation_gradient(md, st);
    timer.stop(kDeformation);
    const StressHealth health = update_stress(md, st);
    timer.stop(kStress);

    double bound = 0;
    for (std::size_t g = 0; g < md.m; ++g) bound = std::max(bound, st.force_bound[g]);
    const bool healthy = health.ok && std::isfinite(bound);
    double red[3] = {-stable_time_step(md, st, scene.time.cfl), bound, healthy ? 0.0 : 1.0};
    comm.max(red, 3);
    timer.stop(kTimeStep);
    if (red[2] > 0) {  // a rank is unhealthy: show the user the state, then stop every rank
      std::ostringstream why;
      if (!health.ok)
        why << "rank " << comm.rank() << ": det F = " << health.J << " at step " << st.step << ", t = " << st.t
            << " s, " << describe_point(md, st, health.point);
      else
        why << "rank " << comm.rank() << ": non-finite forces at step " << st.step << ", t = " << st.t << " s";
      results->write_frame(md, st, st.v, comm);
      comm.check(healthy, why.str() + " (last frame written)");
    }

    const bool last = st.t >= t_end * (1 - 1e-12);
    double dt = -red[0];
    if (!last) {
      dt = std::min(dt, t_end - st.t);
      if (next_output - st.t > 1e-9 * out_dt) dt = std::min(dt, next_output - st.t);
    }
    const double dt_avg = st.step == 0 ? 0.5 * dt : 0.5 * (st.dt_half + dt);
    const FixedScale scale = FixedScale::for_bound(red[1]);
    clear_internal_force(st);
    add_internal_force(md, st, scale, md.boundary_points);
    timer.stop(kInternalForce);
    exchange.start(st.partial);  // the overlap particles' partials travel ...
    timer.stop(kExchange);
    add_internal_force(md, st, scale, md.interior_points);  // ... while the interior is computed
    timer.stop(kInternalForce);
    exchange.finish(st.partial);
    timer.stop(kExchange);

    std::copy(st.v.begin(), st.v.end(), v_old.begin());
    for (std::size_t I = 0; I < md.n; ++I)
      for (int i = 0; i < 3; ++i) {
        st.force[3 * I + i] = scale.real(st.partial[3 * I + i]);
        st.v[3 * I + i] -= dt_avg * st.force[3 * I + i] / md.mass[I];
      }
    apply_symmetry(md, st);
    std::int64_t contacts = 0;
    for (std::size_t w = 0; w < scene.rigid_walls.size(); ++w) {
      const WallResult r = apply_rigid_wall(md, st, scene.rigid_walls[w], dt, dt_avg, v_old);
      st.contact_work += r.work;
      wall_force[w] = r.normal_force;
      contacts += r.contacts;
    }
    timer.stop(kUpdate);

    if (last || st.t >= next_history - 1e-9 * hist_dt) {  // history row at t^n
      row.e = compute_energies(md, st, v_old, comm);
      double counts[1 + 8] = {double(contacts)};
      for (std::size_t w = 0; w < wall_force.size() && w < 8; ++w) counts[1 + w] = wall_force[w];
      comm.sum(counts, 1 + int(std::min<std::size_t>(wall_force.size(), 8)));
      row.time = st.t;
      row.dt = dt;
      row.energy_error = last_error = energy_error(row.e, kinetic0);
      row.contacts = std::int64_t(counts[0]);
      for (std::size_t w = 0; w < row.wall_force.size() && w < 8; ++w) row.wall_force[w] = counts[1 + w];
      if (history) history->write(row);
      next_history += hist_dt;
      if (last_error > scene.health.max_energy_error) {
        results->write_frame(md, st, st.v, comm);
        std::ostringstream why;
        why << "energy error " << last_error << " exceeds health.max_energy_error = " << scene.health.max_energy_error
            << " at step " << st.step << ", t = " << st.t << " s (last frame written); reduce time.cfl";
        comm.check(false, why.str());
      }
    }
    if (last || st.t >= next_output - 1e-9 * out_dt) {  // frame at t^n with vbar
      for (std::size_t k = 0; k < v_old.size(); ++k) v_old[k] = 0.5 * (v_old[k] + st.v[k]);
      results->write_frame(md, st, v_old, comm);
      next_output += out_dt;
      timer.stop(kOutput);
    }
    if (last) break;

    for (std::size_t k = 0; k < st.u.size(); ++k) st.u[k] += dt * st.v[k];
    st.t += dt;
    st.dt_half = dt;
    ++st.step;
    timer.stop(kUpdate);
    if (!opt.quiet && comm.rank() == 0 && comm.wtime() - last_progress > 2.0) {
      last_progress = comm.wtime();
      std::printf("rksolve: t = %.4g s (%5.1f %%), step %lld, dt = %.3g s, energy error %.2e\n", st.t,
                  100 * st.t / t_end, static_cast<long long>(st.step), dt, last_error);
      std::fflush(stdout);
    }
  }

  // solve.json: totals and per-phase times (min/max over ranks)
  const double wall = comm.wtime() - wall0;
  double counts[2] = {0, double(md.m)};
  for (std::size_t I = 0; I < md.n; ++I) counts[0] += md.owned[I];
  comm.sum(counts, 2);
  std::array<double, kPhaseCount> lo = timer.seconds, hi = timer.seconds;
  comm.min(lo.data(), kPhaseCount);
  comm.max(hi.data(), kPhaseCount);
  double mem[2] = {peak_memory_mb(), peak_memory_mb()};
  comm.max(&mem[0], 1);
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
                        {"point_updates_per_s", loop_s > 0 ? counts[1] * double(st.step) / loop_s : 0.0},
                        {"ns_per_point_update", st.step > 0 ? 1e9 * loop_s * comm.size() / (counts[1] * double(st.step)) : 0.0},
                        {"energy_error", last_error},
                        {"initial_kinetic_energy", kinetic0},
                        {"frames", results->frames()},
                        {"peak_memory_mb_max_rank", mem[0]},
                        {"phases", phases}};
    std::ofstream(opt.case_dir + "/solve.json") << j.dump(2) << "\n";
    if (!opt.quiet)
      std::printf("rksolve: done, %lld steps, %.2f s wall (%.0f ns per point update), energy error %.2e\n",
                  static_cast<long long>(st.step), wall, j["ns_per_point_update"].get<double>(), last_error);
  }
}

}  // namespace rk
