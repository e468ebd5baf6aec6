#include "rk/reference_update.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "error.hpp"
#include "local_particles.hpp"
#include "neighbour_grid.hpp"
#include "rk/kinematics.hpp"
#include "rk/local_shapes.hpp"

namespace rk {
namespace {

// What an owner sends of each of its particles to the ranks that need it: global id, X (t = 0), d,
// v, d^ref, volume, spacing at t = 0, flags, owner, temperature coefficient and friction heat (with
// conduction), the stable step's mode (with time.stable_step = frequency), its own last step (with multi-rate steps).
enum { kGid, kX = 1, kU = 4, kV = 7, kRef = 10, kVolume = 13, kSpacing0, kFlags, kOwner, kTemperature, kSurfaceHeat, kMode,
       kDtHalf = kMode + 3, kRecord };

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
    r[kDtHalf] = st.particle_dt_half.empty() ? 0.0 : st.particle_dt_half[I];
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

// Support spacings on the new reference. Spheres of the t = 0 size keep the number of particles
// per support (plastic flow keeps volume), but where the material has stretched (the hoop direction
// of a flange) a point can lose the particles on one side and its moment matrix degenerates. So:
// start from h_I at t = 0; every point whose neighbours surround it poorly (neighbour_spread below
// kPoor, a decade below the worst point of a fresh lattice, 0.3) grows by kGrow the spacing of
// the particles within kReach supports of it (a modest growth over the poor point's neighbourhood),
// once: the growth must not feed on itself (docs/decisions.md, "Reference updates: supports grown by
// a scale-free spread, once"). This rank's points flag particles of its halo (ascending); share_growth
// tells every rank that holds them, so every rank count grows the same ones.
constexpr double kPoor = 0.03, kGrow = 1.25, kReach = 1.5;

std::vector<std::int32_t> flag_growth(const Model& md, const Scene& scene, const std::vector<double>& Xr,
                                      const std::vector<double>& volume, const std::vector<std::uint8_t>& body,
                                      const std::vector<double>& spacing) {
  const std::size_t total = spacing.size();
  const Kernel kernel = parse_kernel(scene.discretization.kernel);
  std::vector<double> radius(total), reach(total);
  std::vector<std::int32_t> candidates, found, grow;
  std::vector<std::uint8_t> flagged(total, 0);  // (a poor point's neighbourhood overlaps the next one's)
  for (std::size_t I = 0; I < total; ++I) radius[I] = scene.discretization.dilation * spacing[I], reach[I] = kReach * radius[I];
  const NeighbourGrid grid(Xr.data(), radius.data(), total), near(Xr.data(), reach.data(), total);
  const RkParticles particles{Xr.data(), volume.data(), radius.data()};
  std::vector<std::uint8_t> point_body(md.m);  // a point's body: its cell's nodes'
  for (std::size_t c = 0; c < md.cells; ++c)
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g)
      point_body[std::size_t(g)] = std::uint8_t(cell_body(md, c));
  for (std::size_t c = 0; c < md.cells; ++c) {
    const auto g0 = std::size_t(md.cell_points[c]), g1 = std::size_t(md.cell_points[c + 1]);
    candidates.clear();
    grid.near_group(&md.point_X[3 * g0], g1 - g0, candidates);
    for (auto g = g0; g < g1; ++g) {
      found.clear();
      grid.covering_among(&md.point_X[3 * g], candidates, found);
      std::erase_if(found, [&](std::int32_t J) { return body[std::size_t(J)] != point_body[g]; });
      if (neighbour_spread(&md.point_X[3 * g], found, particles, kernel) >= kPoor) continue;
      found.clear();
      near.covering(&md.point_X[3 * g], found);
      for (auto J : found) flagged[std::size_t(J)] = 1;
    }
  }
  for (std::size_t J = 0; J < total; ++J)
    if (flagged[J]) grow.push_back(std::int32_t(J));
  return grow;  // ascending
}

// Values grouped by destination rank, for Comm::exchange.
struct Outbox {
  std::vector<std::vector<double>> to;
  explicit Outbox(std::size_t ranks) : to(ranks) {}
  // sends everything; from[r] holds what rank r sent this one
  std::vector<std::vector<double>> exchange(const Comm& comm) const {
    std::vector<double> send, received;
    std::vector<int> counts, recv_counts;
    bool fits = true;  // MPI's int counts; checked on every rank before the exchange, so none is left in it
    for (const auto& list : to) {
      send.insert(send.end(), list.begin(), list.end());
      fits = fits && list.size() <= std::size_t(std::numeric_limits<int>::max());
      counts.push_back(int(std::min(list.size(), std::size_t(std::numeric_limits<int>::max()))));
    }
    comm.check(fits, "reference update: rank " + std::to_string(comm.rank()) + " would send another rank more than 2^31 values");
    comm.exchange(send, counts, received, recv_counts);
    std::vector<std::vector<double>> from(to.size());
    auto at = received.begin();
    for (std::size_t r = 0; r < from.size(); ++r) {
      from[r].assign(at, at + recv_counts[r]);
      at += recv_counts[r];
    }
    return from;
  }
};

// The owned particles' records (every rank's) that this rank needs on the new reference, its halo,
// in ascending global id. A rank needs every particle whose support, grown once and searched kReach
// wide (flag_growth), can reach one of its points or owned particles, and its cells' nodes. Every
// owner sends its records to each rank whose box (around those points and particles) lies within kReach
// t = 0 supports of them, and the cell nodes a rank asks for by id: memory and work follow the rank's
// share, not the part.
struct Halo {
  std::vector<std::int32_t> gid;  // ascending
  std::vector<double> records;    // kRecord per particle
  std::vector<std::vector<std::int32_t>> sent;  // per rank: the owned records sent it (indices into this rank's)
  std::size_t size() const { return gid.size(); }
  const double* operator[](std::size_t k) const { return &records[kRecord * k]; }
  std::int64_t find(std::int64_t id) const {  // position of a global id, -1 if not held
    const auto it = std::lower_bound(gid.begin(), gid.end(), id);
    return it != gid.end() && *it == id ? it - gid.begin() : -1;
  }
};

Halo gather_halo(const Model& md, const Scene& scene, const std::vector<double>& mine, const Comm& comm) {
  const std::size_t owned = mine.size() / kRecord;
  auto position = [&](std::size_t k, int i) { return mine[kRecord * k + kX + i] + mine[kRecord * k + kRef + i]; };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> box{kInf, kInf, kInf, -kInf, -kInf, -kInf};
  auto cover = [&](int i, double x) { box[i] = std::min(box[i], x), box[3 + i] = std::max(box[3 + i], x); };
  for (std::size_t g = 0; g < md.m; ++g)
    for (int i = 0; i < 3; ++i) cover(i, md.point_X[3 * g + i]);
  for (std::size_t k = 0; k < owned; ++k)
    for (int i = 0; i < 3; ++i) cover(i, position(k, i));
  const std::vector<double> boxes = comm.gather_all(box);

  Outbox asks(std::size_t(md.ranks));  // the cell nodes this rank needs, by owner
  for (auto node : md.cell_nodes)
    if (!md.owned[node]) asks.to[std::size_t(md.owner[node])].push_back(double(md.global_id[node]));
  for (auto& list : asks.to) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  const std::vector<std::vector<double>> asked = asks.exchange(comm);

  Halo halo;
  halo.sent.resize(std::size_t(md.ranks));
  Outbox records(std::size_t(md.ranks));
  // flag_growth's widest search; the grown supports (kGrow < kReach) lie inside it
  auto reach_of = [&](std::size_t k) { return (1 + 1e-12) * kReach * scene.discretization.dilation * mine[kRecord * k + kSpacing0]; };
  double widest = 0;
  for (std::size_t k = 0; k < owned; ++k) widest = std::max(widest, reach_of(k));
  for (std::size_t r = 0; r < std::size_t(md.ranks); ++r) {
    const double* b = &boxes[6 * r];
    bool apart = false;  // this rank's box, widened by the widest reach, misses rank r's
    for (int i = 0; i < 3; ++i) apart = apart || box[i] - widest > b[3 + i] || box[3 + i] + widest < b[i];
    if (apart && asked[r].empty()) continue;
    auto ask = asked[r].begin();
    for (std::size_t k = 0; k < owned; ++k) {
      const double id = mine[kRecord * k + kGid];
      while (ask != asked[r].end() && *ask < id) ++ask;
      double d2 = 0;  // from the particle to the box
      for (int i = 0; i < 3; ++i) {
        const double x = position(k, i), d = std::max({b[i] - x, x - b[3 + i], 0.0});
        d2 += d * d;
      }
      const double reach = reach_of(k);
      if (d2 > reach * reach && (ask == asked[r].end() || *ask != id)) continue;
      halo.sent[r].push_back(std::int32_t(k));
      records.to[r].insert(records.to[r].end(), &mine[kRecord * k], &mine[kRecord * (k + 1)]);
    }
  }
  std::vector<double> all;
  for (const auto& from : records.exchange(comm)) all.insert(all.end(), from.begin(), from.end());
  std::vector<std::size_t> order(all.size() / kRecord);
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[kRecord * a] < all[kRecord * b]; });
  bool unique = true;
  for (auto k : order) {
    const auto id = std::int32_t(all[kRecord * k + kGid]);
    unique = unique && (halo.gid.empty() || halo.gid.back() != id);
    halo.gid.push_back(id);
    halo.records.insert(halo.records.end(), &all[kRecord * k], &all[kRecord * (k + 1)]);
  }
  comm.check(unique, "reference update: two ranks own the same particle (global ids not unique)");
  bool complete = true;
  for (auto node : md.cell_nodes) complete = complete && halo.find(md.global_id[node]) >= 0;
  comm.check(complete, "reference update: a node of rank " + std::to_string(md.rank) + "'s cells is owned by no rank");
  return halo;
}

// The position of global id `id` among this rank's owned records (ascending global id).
std::size_t owned_position(const std::vector<double>& mine, double id) {
  std::size_t lo = 0, hi = mine.size() / kRecord;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (mine[kRecord * mid + kGid] < id) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// Grows the spacing of every halo particle that some rank's points flagged: the flags go to the
// particles' owners and back to every rank the owners sent them to.
void share_growth(const Halo& halo, const std::vector<std::int32_t>& flagged, const std::vector<double>& mine,
                  std::vector<double>& spacing, const Comm& comm) {
  Outbox to_owner(halo.sent.size());
  for (auto k : flagged) to_owner.to[std::size_t(halo[std::size_t(k)][kOwner])].push_back(double(halo.gid[std::size_t(k)]));
  std::vector<std::uint8_t> grown(mine.size() / kRecord, 0);  // of this rank's owned particles
  for (const auto& ids : to_owner.exchange(comm))
    for (double id : ids) grown[owned_position(mine, id)] = 1;
  Outbox back(halo.sent.size());
  for (std::size_t r = 0; r < halo.sent.size(); ++r)
    for (auto k : halo.sent[r])
      if (grown[std::size_t(k)]) back.to[r].push_back(mine[kRecord * std::size_t(k) + kGid]);
  for (const auto& ids : back.exchange(comm))
    for (double id : ids) spacing[std::size_t(halo.find(std::int64_t(id)))] *= kGrow;
}

// The overlap maps of the new local sets (local_particles.hpp's overlap_maps, without any rank
// holding the others' sets): each rank tells the owners which particles it holds, and each owner
// answers with every holder of each.
void share_holders(const Halo& halo, const std::vector<std::int32_t>& local, const std::vector<double>& mine, int rank,
                   std::vector<std::int32_t>& neighbour_ranks, std::vector<std::vector<std::int32_t>>& maps, const Comm& comm) {
  const std::size_t ranks = halo.sent.size(), owned = mine.size() / kRecord;
  Outbox held(ranks);
  std::vector<std::vector<std::int32_t>> asked_of(ranks);  // per owner, the local indices told
  for (std::size_t k = 0; k < local.size(); ++k) {
    const auto owner = std::size_t(halo[std::size_t(local[k])][kOwner]);
    held.to[owner].push_back(double(halo.gid[std::size_t(local[k])]));
    asked_of[owner].push_back(std::int32_t(k));
  }
  const std::vector<std::vector<double>> holds = held.exchange(comm);
  std::vector<std::int32_t> start(owned + 1, 0), holder;  // CSR: the ranks holding each owned particle
  for (const auto& ids : holds)
    for (double id : ids) ++start[owned_position(mine, id) + 1];
  for (std::size_t k = 0; k < owned; ++k) start[k + 1] += start[k];
  holder.resize(std::size_t(start[owned]));
  std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t r = 0; r < ranks; ++r)
    for (double id : holds[r]) holder[std::size_t(fill[owned_position(mine, id)]++)] = std::int32_t(r);
  Outbox answer(ranks);
  for (std::size_t r = 0; r < ranks; ++r)
    for (double id : holds[r]) {
      const std::size_t k = owned_position(mine, id);
      answer.to[r].push_back(double(start[k + 1] - start[k]));
      for (auto h = start[k]; h < start[k + 1]; ++h) answer.to[r].push_back(holder[std::size_t(h)]);
    }
  std::vector<std::pair<std::int32_t, std::int32_t>> shared;  // (other holder, local index)
  const std::vector<std::vector<double>> answers = answer.exchange(comm);
  for (std::size_t o = 0; o < ranks; ++o) {
    std::size_t at = 0;
    for (auto k : asked_of[o]) {
      const auto count = std::size_t(answers[o][at++]);
      for (std::size_t h = 0; h < count; ++h, ++at)
        if (int(answers[o][at]) != rank) shared.emplace_back(std::int32_t(answers[o][at]), k);
    }
  }
  std::sort(shared.begin(), shared.end());
  neighbour_ranks.clear(), maps.clear();
  for (const auto& [p, k] : shared) {
    if (neighbour_ranks.empty() || neighbour_ranks.back() != p) neighbour_ranks.push_back(p), maps.emplace_back();
    maps.back().push_back(k);
  }
}

// The owned particles' new reference displacements x_I - X_I and velocities v^h(X_I), evaluated with
// the old shape functions at the particles (update_reference below); the search's grid goes with it.
void material_at_particles(const Model& md, const State& st, const Scene& scene, const Projection& project,
                           std::vector<double>& moved, std::vector<double>& velocity) {
  const LocalShapes shapes(md.Xr, md.volume, md.spacing, md.body, scene);
  std::vector<std::int32_t> cols;
  std::vector<double> N;
  for (std::size_t I = 0; I < md.n; ++I) {
    if (!md.owned[I]) continue;
    cols.clear(), N.clear();
    double x[3] = {md.Xr[3 * I], md.Xr[3 * I + 1], md.Xr[3 * I + 2]};
    if (shapes.append(&md.Xr[3 * I], md.body[I], cols, N).regular) {
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
}

}  // namespace

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
  std::vector<double> moved(3 * md.n), velocity(st.v);
  material_at_particles(md, st, scene, project, moved, velocity);
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
  const std::vector<double> mine = owned_records(md, st);
  const Halo halo = gather_halo(md, scene, mine, comm);
  const std::size_t held = halo.size();
  std::vector<double> Xr(3 * held), volume(held), spacing(held);  // the new reference: X + d^ref
  std::vector<std::uint8_t> body(held);
  for (std::size_t k = 0; k < held; ++k) {
    for (int i = 0; i < 3; ++i) Xr[3 * k + i] = halo[k][kX + i] + halo[k][kRef + i];
    volume[k] = halo[k][kVolume], spacing[k] = halo[k][kSpacing0];
    body[k] = std::uint8_t(body_of(std::uint8_t(halo[k][kFlags])));
  }
  share_growth(halo, flag_growth(md, scene, Xr, volume, body, spacing), mine, spacing, comm);
  std::vector<double> radius(held);
  for (std::size_t k = 0; k < held; ++k) radius[k] = scene.discretization.dilation * spacing[k];
  const NeighbourGrid grid(Xr.data(), radius.data(), held);
  LocalParticleRequest request{grid, Xr.data(), {}, md.point_X, {}, md.cell_points};
  for (auto node : md.cell_nodes) request.cell_nodes.push_back(std::int32_t(halo.find(md.global_id[node])));
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I]) request.owned.push_back(std::int32_t(halo.find(md.global_id[I])));
  const std::vector<std::int32_t> local = local_particles(request);  // halo positions, ascending global id

  Subdomain sub;
  sub.rank = md.rank, sub.ranks = md.ranks;
  std::vector<std::int32_t> index(held, -1);  // halo position -> local index
  std::vector<double> X0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const auto h = std::size_t(local[k]);
    index[h] = std::int32_t(k);
    sub.global_id.push_back(halo.gid[h]);
    for (int i = 0; i < 3; ++i) sub.X.push_back(Xr[3 * h + i]), X0.push_back(halo[h][kX + i]);
    sub.volume.push_back(halo[h][kVolume]);
    sub.spacing.push_back(spacing[h]);
    sub.owner.push_back(std::int32_t(halo[h][kOwner]));
    sub.flags.push_back(std::uint8_t(halo[h][kFlags]));
  }
  auto local_of = [&](std::size_t node) { return index[std::size_t(halo.find(md.global_id[node]))]; };
  sub.cell_global_id = md.cell_global_id;
  sub.cell_node_offsets = md.cell_node_offsets;
  for (auto node : md.cell_nodes) sub.cell_nodes.push_back(local_of(std::size_t(node)));
  sub.surface_face_offsets = md.surface_face_offsets, sub.surface_face_cell = md.surface_face_cell;
  for (auto node : md.surface_face_nodes) sub.surface_face_nodes.push_back(local_of(std::size_t(node)));
  sub.point_X = md.point_X;
  sub.point_weight = md.weight;
  for (std::size_t c = 0; c < md.cells; ++c)
    sub.point_cell.insert(sub.point_cell.end(), std::size_t(md.cell_points[c + 1] - md.cell_points[c]), std::int32_t(c));
  share_holders(halo, local, mine, md.rank, sub.neighbour_ranks, sub.overlap, comm);
  sub.dies = md.dies;

  // The old points' neighbours and shape functions are not read past here: the new ones are built in
  // their storage, so an update holds one set of them, not two (docs/performance.md, "Scale model").
  Model next = build_model(sub, scene, &X0, &md);
  scale_mass(next, md.mass_scaling);
  next.spacing0.clear();
  for (auto h : local) next.spacing0.push_back(halo[std::size_t(h)][kSpacing0]);
  // The contact's stable step takes the shorter of the cells' t = 0 edges and their edges now, the step at
  // most step_growth times that (build_model).
  st.u.assign(3 * next.n, 0.0), st.v.assign(3 * next.n, 0.0), st.u_ref.assign(3 * next.n, 0.0);
  for (std::size_t k = 0; k < next.n; ++k)
    for (int i = 0; i < 3; ++i) {
      const double* r = halo[std::size_t(local[k])];
      st.u[3 * k + i] = r[kU + i], st.v[3 * k + i] = r[kV + i], st.u_ref[3 * k + i] = r[kRef + i];
    }
  if (!st.stiff_mode.empty()) {
    st.stiff_mode.resize(3 * next.n);
    for (std::size_t k = 0; k < next.n; ++k)
      for (int i = 0; i < 3; ++i) st.stiff_mode[3 * k + i] = halo[std::size_t(local[k])][kMode + i];
  }
  if (!st.particle_dt_half.empty()) {
    st.particle_dt_half.resize(next.n);
    for (std::size_t k = 0; k < next.n; ++k) st.particle_dt_half[k] = halo[std::size_t(local[k])][kDtHalf];
  }
  if (!st.particle_temperature.empty()) {
    st.particle_temperature.resize(next.n);
    st.surface_heat.assign(next.n, 0.0);
    for (std::size_t k = 0; k < next.n; ++k) {
      st.particle_temperature[k] = halo[std::size_t(local[k])][kTemperature];
      if (next.owned[k]) st.surface_heat[k] = halo[std::size_t(local[k])][kSurfaceHeat];  // held by the owner only
    }
  }
  st.force.assign(3 * next.n, 0.0);
  st.partial.assign(kForceStride * next.n, Fixed(0));
  md = std::move(next);
}

}  // namespace rk
