#include "rk/reference_update.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "error.hpp"
#include "local_particles.hpp"
#include "neighbour_grid.hpp"
#include "rk/kinematics.hpp"
#include "rk/local_shapes.hpp"

namespace rk {
namespace {

// What every rank learns about each owned particle: global id, X (t = 0), d, v, d^ref, volume,
// spacing at t = 0, flags, owner, temperature coefficient and friction heat (with conduction), the
// stable step's mode (with time.stable_step = frequency).
enum { kGid, kX = 1, kU = 4, kV = 7, kRef = 10, kVolume = 13, kSpacing0, kFlags, kOwner, kTemperature, kSurfaceHeat, kMode, kRecord = kMode + 3 };

std::vector<double> owned_records(const Model& md, const State& st) {
  std::vector<double> out;
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    double r[kRecord];
    r[kGid] = double(md.global_id[I]);
    for (int i = 0; i < 3; ++i) {
      r[kX + i] = md.X[3 * I + i];
      r[kU + i] = st.u[3 * I + i];
      r[kV + i] = st.v[3 * I + i];
      r[kRef + i] = st.u_ref[3 * I + i];
    }
    r[kVolume] = md.volume[I], r[kSpacing0] = md.spacing0[I];
    r[kFlags] = double((md.surface[I] ? kSurface : 0) | (md.body[I] << kBodyShift));
    r[kOwner] = md.rank;
    r[kTemperature] = st.particle_temperature.empty() ? 0.0 : st.particle_temperature[I];
    r[kSurfaceHeat] = st.surface_heat.empty() ? 0.0 : st.surface_heat[I];
    for (int i = 0; i < 3; ++i) r[kMode + i] = st.stiff_mode.empty() ? 0.0 : st.stiff_mode[3 * I + i];
    out.insert(out.end(), r, r + kRecord);
  }
  return out;
}

// S <- F S F^T for a symmetric S stored xx, yy, zz, xy, yz, zx.
void push_forward(const double F[9], double* S) {
  const double C[9] = {S[0], S[3], S[5], S[3], S[1], S[4], S[5], S[4], S[2]};
  double FC[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) FC[3 * i + j] = F[3 * i] * C[j] + F[3 * i + 1] * C[3 + j] + F[3 * i + 2] * C[6 + j];
  auto b = [&](int i, int j) { return FC[3 * i] * F[3 * j] + FC[3 * i + 1] * F[3 * j + 1] + FC[3 * i + 2] * F[3 * j + 2]; };
  S[0] = b(0, 0), S[1] = b(1, 1), S[2] = b(2, 2), S[3] = b(0, 1), S[4] = b(1, 2), S[5] = b(2, 0);
}

// Every rank's list, in rank order (set-up only).
std::vector<std::vector<std::int32_t>> gather_lists(const std::vector<std::int32_t>& mine, const Comm& comm) {
  const std::vector<double> counts = comm.gather_all({double(mine.size())});
  const std::vector<double> all = comm.gather_all(std::vector<double>(mine.begin(), mine.end()));
  std::vector<std::vector<std::int32_t>> lists(counts.size());
  std::size_t k = 0;
  for (std::size_t r = 0; r < counts.size(); ++r)
    for (std::size_t j = 0; j < std::size_t(counts[r]); ++j) lists[r].push_back(std::int32_t(all[k++]));
  return lists;
}

// Support spacings on the new reference. Spheres of the t = 0 size keep the number of particles
// per support (plastic flow keeps volume), but where the material has stretched (the hoop direction
// of a flange) a point can lose the particles on one side and its moment matrix degenerates. So:
// start from h_I at t = 0; every point whose neighbours surround it poorly (neighbour_spread below
// kPoor, a decade below the worst point of a fresh lattice, 0.3) grows by kGrow the spacing of
// the particles within kReach supports of it (a modest growth over the poor point's neighbourhood),
// once: the growth must not feed on itself (docs/decisions.md, "Reference updates: supports grown by
// a scale-free spread, once"). The points are tested on their ranks and the grown particles are
// shared, so every rank count grows the same ones.
std::vector<double> conditioned_spacing(const Model& md, const Scene& scene, const std::vector<double>& Xr,
                                        const std::vector<double>& volume, const std::vector<std::uint8_t>& body,
                                        std::vector<double> spacing, const Comm& comm) {
  constexpr double kPoor = 0.03, kGrow = 1.25, kReach = 1.5;
  const std::size_t total = spacing.size();
  const Kernel kernel = parse_kernel(scene.discretization.kernel);
  std::vector<double> radius(total), reach(total);
  std::vector<std::int32_t> found, grow;
  for (std::size_t I = 0; I < total; ++I) radius[I] = scene.discretization.dilation * spacing[I], reach[I] = kReach * radius[I];
  const NeighbourGrid grid(Xr.data(), radius.data(), total), near(Xr.data(), reach.data(), total);
  const RkParticles particles{Xr.data(), volume.data(), radius.data()};
  std::vector<std::uint8_t> point_body(md.m);  // a point's body: its cell's nodes'
  for (std::size_t c = 0; c < md.cells; ++c)
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g)
      point_body[std::size_t(g)] = std::uint8_t(cell_body(md, c));
  for (std::size_t g = 0; g < md.m; ++g) {
    found.clear();
    grid.covering(&md.point_X[3 * g], found);
    std::erase_if(found, [&](std::int32_t J) { return body[std::size_t(J)] != point_body[g]; });
    if (neighbour_spread(&md.point_X[3 * g], found, particles, kernel) >= kPoor) continue;
    found.clear();
    near.covering(&md.point_X[3 * g], found);
    grow.insert(grow.end(), found.begin(), found.end());
  }
  std::sort(grow.begin(), grow.end());
  grow.erase(std::unique(grow.begin(), grow.end()), grow.end());
  std::vector<std::uint8_t> grown(total, 0);
  for (const auto& list : gather_lists(grow, comm))
    for (auto I : list) grown[I] = 1;
  for (std::size_t I = 0; I < total; ++I)
    if (grown[I]) spacing[I] *= kGrow;
  return spacing;
}

}  // namespace

double largest_strain_since_update(const Model& md, const State& st) {
  double worst = 0;
  for (std::size_t g = 0; g < md.m; ++g) {
    const double* F = &st.F[9 * g];
    double e2 = 0;  // |F^T F - I|^2
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double c = F[a] * F[b] + F[3 + a] * F[3 + b] + F[6 + a] * F[6 + b] - (a == b ? 1.0 : 0.0);
        e2 += c * c;
      }
    worst = std::max(worst, e2);
  }
  return 0.5 * std::sqrt(worst);
}

void update_reference(Model& md, State& st, const Scene& scene, const Comm& comm, const Projection& project) {
  compute_deformation_gradient(md, st);
  if (st.u_ref.empty()) st.u_ref.assign(st.u.size(), 0.0), st.J_ref.assign(md.m, 1.0);
  for (std::size_t c = 0; c < md.cells; ++c) {
    const auto g0 = std::size_t(md.cell_points[c]), g1 = std::size_t(md.cell_points[c + 1]);
    double volume = 0, weight = 0;  // the cell's: sum w_g J_ref J, sum w_g
    for (auto g = g0; g < g1; ++g) {
      double x[3];  // x_g = X_g + u^h(X_g)
      point_position(md, st, g, x);
      // Dies and walls hold the field itself (contact/die_contact.hpp), so a point in one is only as
      // deep as its penalty spring and stays there: putting it back would cut the spring's layer off
      // the material at every update (docs/decisions.md, "Contact").
      for (int i = 0; i < 3; ++i) md.point_X[3 * g + i] = x[i];
      // C_p^-1 <- Fbar C_p^-1 Fbar^T, the trial elastic left Cauchy-Green tensor of this state
      const double ratio = md.fbar ? std::cbrt(st.cell_J[c] / st.J[g]) : 1.0;
      double F[9];
      for (int i = 0; i < 9; ++i) F[i] = ratio * st.F[9 * g + i];
      push_forward(F, &st.cp_inv[6 * g]);
      volume += md.weight[g] * st.J_ref[g] * st.J[g], weight += md.weight[g];
    }
    // The points' volumes on the new reference, w_g J_ref. With F-bar the material responds to its
    // cell's volume change, not to a point's own J, so every point of a cell takes the cell's mean:
    // the points' own J scatter within a cell, and carried into their volumes the next stage's F-bar
    // mean (by w_g) would no longer measure the cell's volume (docs/decisions.md, "Reference updates:
    // every point of an F-bar cell takes the cell's volume").
    for (auto g = g0; g < g1; ++g) st.J_ref[g] = md.fbar ? volume / weight : st.J_ref[g] * st.J[g];
  }
  // The owned particles' new reference positions and velocities: those of the material they sit in,
  // x_I = X_I + u^h(X_I) and v^h(X_I) (coefficients that the old shape functions smoothed away would
  // strain the new ones), positions put back onto their faces; a particle in a die or a wall stays
  // where its penalty spring holds it, as the points do (the contact holds u^h(X_I), so the spring
  // keeps its depth across the update). The coefficients become d_I = x_I - X_I and v_I = v^h; the
  // kinetic energy this removes is booked as update_work (docs/decisions.md, "Reference updates: the
  // particles take the material's position and velocity"). Nothing here throws: every rank must
  // reach the rebuild's collectives.
  const LocalShapes shapes(md.Xr, md.volume, md.spacing, md.body, scene);
  std::vector<std::int32_t> cols;
  std::vector<double> N, dN, moved(3 * md.n), velocity(st.v);
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    cols.clear(), N.clear(), dN.clear();
    double x[3] = {md.Xr[3 * I], md.Xr[3 * I + 1], md.Xr[3 * I + 2]};
    if (shapes.append(&md.Xr[3 * I], md.body[I], cols, N, dN).regular) {
      for (int i = 0; i < 3; ++i) velocity[3 * I + i] = 0;
      for (std::size_t k = 0; k < cols.size(); ++k)
        for (int i = 0; i < 3; ++i) {
          x[i] += N[k] * (st.u[3 * std::size_t(cols[k]) + i] - st.u_ref[3 * std::size_t(cols[k]) + i]);
          velocity[3 * I + i] += N[k] * st.v[3 * std::size_t(cols[k]) + i];
        }
    } else {  // u^h cannot be evaluated there (a particle left alone): it stays at X + d
      for (int i = 0; i < 3; ++i) x[i] += st.u[3 * I + i] - st.u_ref[3 * I + i];
    }
    project(I, x);
    for (int i = 0; i < 3; ++i) moved[3 * I + i] = x[i] - md.X[3 * I + i];
  }
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I])
      for (int i = 0; i < 3; ++i) {
        st.update_work += 0.5 * md.mass[I] * (velocity[3 * I + i] * velocity[3 * I + i] - st.v[3 * I + i] * st.v[3 * I + i]);
        st.u[3 * I + i] = st.u_ref[3 * I + i] = moved[3 * I + i], st.v[3 * I + i] = velocity[3 * I + i];
      }
  ++st.reference_updates;
  rebuild_on_reference(md, st, scene, comm);
}

void rebuild_on_reference(Model& md, State& st, const Scene& scene, const Comm& comm) {
  const std::vector<double> all = comm.gather_all(owned_records(md, st));
  const std::size_t total = all.size() / kRecord;
  std::vector<const double*> record(total, nullptr);  // by global id
  for (std::size_t k = 0; k < total; ++k) {
    const auto gid = std::size_t(all[kRecord * k + kGid]);
    if (gid >= total || record[gid])
      throw Error("reference update: the owned particles' global ids are not 0.." + std::to_string(total - 1));
    record[gid] = &all[kRecord * k];
  }
  std::vector<double> Xr(3 * total), volume(total), h0(total);  // the new reference: X + d^ref
  std::vector<std::uint8_t> body(total);
  for (std::size_t I = 0; I < total; ++I) {
    for (int i = 0; i < 3; ++i) Xr[3 * I + i] = record[I][kX + i] + record[I][kRef + i];
    volume[I] = record[I][kVolume], h0[I] = record[I][kSpacing0];
    body[I] = std::uint8_t(body_of(std::uint8_t(record[I][kFlags])));
  }
  const std::vector<double> spacing = conditioned_spacing(md, scene, Xr, volume, body, h0, comm);
  std::vector<double> radius(total);
  for (std::size_t I = 0; I < total; ++I) radius[I] = scene.discretization.dilation * spacing[I];
  const NeighbourGrid grid(Xr.data(), radius.data(), total);
  LocalParticleRequest request{grid, Xr.data(), {}, md.point_X, {}};
  for (auto node : md.cell_nodes) request.cell_nodes.push_back(std::int32_t(md.global_id[node]));
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I]) request.owned.push_back(std::int32_t(md.global_id[I]));
  const std::vector<std::int32_t> local = local_particles(request);
  const std::vector<std::vector<std::int32_t>> every = gather_lists(local, comm);

  Subdomain sub;
  sub.rank = md.rank, sub.ranks = md.ranks;
  std::vector<std::int32_t> index(total, -1);
  std::vector<double> X0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const double* r = record[local[k]];
    index[local[k]] = std::int32_t(k);
    sub.global_id.push_back(local[k]);
    for (int i = 0; i < 3; ++i) sub.X.push_back(Xr[3 * std::size_t(local[k]) + i]), X0.push_back(r[kX + i]);
    sub.volume.push_back(r[kVolume]);
    sub.spacing.push_back(spacing[local[k]]);
    sub.owner.push_back(std::int32_t(r[kOwner]));
    sub.flags.push_back(std::uint8_t(r[kFlags]));
  }
  sub.cell_global_id = md.cell_global_id;
  sub.cell_node_offsets = md.cell_node_offsets;
  for (auto node : md.cell_nodes) sub.cell_nodes.push_back(index[md.global_id[node]]);
  sub.surface_face_offsets = md.surface_face_offsets, sub.surface_face_cell = md.surface_face_cell;
  for (auto node : md.surface_face_nodes) sub.surface_face_nodes.push_back(index[md.global_id[node]]);
  sub.point_X = md.point_X;
  sub.point_weight = md.weight;
  for (std::size_t c = 0; c < md.cells; ++c)
    sub.point_cell.insert(sub.point_cell.end(), std::size_t(md.cell_points[c + 1] - md.cell_points[c]), std::int32_t(c));
  overlap_maps(every, md.rank, sub.neighbour_ranks, sub.overlap);
  sub.dies = md.dies;

  Model next = build_model(sub, scene, &X0);
  scale_mass(next, md.mass_scaling);
  next.spacing0.clear();
  for (auto I : local) next.spacing0.push_back(record[I][kSpacing0]);
  // The stable step takes the shorter of the cells' t = 0 edges and their edges now (build_model).
  st.u.assign(3 * next.n, 0.0), st.v.assign(3 * next.n, 0.0), st.u_ref.assign(3 * next.n, 0.0);
  for (std::size_t k = 0; k < next.n; ++k)
    for (int i = 0; i < 3; ++i) {
      const double* r = record[local[k]];
      st.u[3 * k + i] = r[kU + i], st.v[3 * k + i] = r[kV + i], st.u_ref[3 * k + i] = r[kRef + i];
    }
  if (!st.stiff_mode.empty()) {
    st.stiff_mode.resize(3 * next.n);
    for (std::size_t k = 0; k < next.n; ++k)
      for (int i = 0; i < 3; ++i) st.stiff_mode[3 * k + i] = record[local[k]][kMode + i];
  }
  if (!st.particle_temperature.empty()) {
    st.particle_temperature.resize(next.n);
    st.surface_heat.assign(next.n, 0.0);
    for (std::size_t k = 0; k < next.n; ++k) {
      st.particle_temperature[k] = record[local[k]][kTemperature];
      if (next.owned[k]) st.surface_heat[k] = record[local[k]][kSurfaceHeat];  // held by the owner only
    }
  }
  st.force.assign(3 * next.n, 0.0);
  st.partial.assign(3 * next.n, Fixed(0));
  md = std::move(next);
}

}  // namespace rk
