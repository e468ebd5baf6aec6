#include "partition.hpp"

#include <metis.h>

#include <algorithm>
#include <numeric>

#include "error.hpp"
#include "hash.hpp"
#include "local_particles.hpp"
#include "neighbour_grid.hpp"

namespace rk {

std::vector<std::int32_t> partition_cells(const VolumeMesh& mesh, const Discretization& disc, int ranks,
                                          const std::string& method) {
  const std::size_t nc = mesh.cell_count();
  if (ranks < 1) throw Error("--ranks must be at least 1");
  if (std::size_t(ranks) > nc)
    throw Error("--ranks " + std::to_string(ranks) + " exceeds the " + std::to_string(nc) + " integration cells");
  if (ranks == 1) return std::vector<std::int32_t>(nc, 0);  // METIS 5.1 crashes when asked for one part
  if (method != "metis-kway" && method != "metis-recursive")
    throw Error("--partitioner '" + method + "' is not one of: metis-kway, metis-recursive");

  std::vector<idx_t> eptr(mesh.cell_offsets.begin(), mesh.cell_offsets.end());
  std::vector<idx_t> eind(mesh.cell_nodes.begin(), mesh.cell_nodes.end());
  std::vector<idx_t> vwgt(nc, 0);
  for (auto c : disc.point_cell) ++vwgt[c];
  bool all_hex = true;
  for (std::size_t c = 0; c < nc; ++c) all_hex &= mesh.cell_offsets[c + 1] - mesh.cell_offsets[c] == 8;
  idx_t ne = idx_t(nc), nn = idx_t(mesh.node_count()), ncommon = all_hex ? 4 : 3, nparts = ranks, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_PTYPE] = method == "metis-kway" ? METIS_PTYPE_KWAY : METIS_PTYPE_RB;
  options[METIS_OPTION_SEED] = 7;  // deterministic partitions
  std::vector<idx_t> epart(nc), npart(mesh.node_count());
  int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), vwgt.data(), nullptr, &ncommon, &nparts,
                                  nullptr, options, &objval, epart.data(), npart.data());
  if (status != METIS_OK) throw Error("METIS failed to partition the integration cells (status " + std::to_string(status) + ")");
  return std::vector<std::int32_t>(epart.begin(), epart.end());
}

std::vector<Subdomain> build_subdomains(const SubdomainRequest& r) {
  const std::size_t n = r.mesh.node_count(), nc = r.mesh.cell_count();
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = r.dilation * r.disc.spacing[i];
  NeighbourGrid grid(r.mesh.X.data(), radius.data(), n);

  // Owner: the rank of the lowest-numbered cell that has the particle as a node.
  std::vector<std::int32_t> owner(n, -1);
  for (std::size_t c = 0; c < nc; ++c)
    for (auto k = r.mesh.cell_offsets[c]; k < r.mesh.cell_offsets[c + 1]; ++k)
      if (owner[r.mesh.cell_nodes[k]] < 0) owner[r.mesh.cell_nodes[k]] = r.cell_rank[c];

  std::vector<std::vector<std::int32_t>> cells_of(r.ranks), points_of(r.ranks);
  for (std::size_t c = 0; c < nc; ++c) cells_of[r.cell_rank[c]].push_back(std::int32_t(c));
  for (std::size_t g = 0; g < r.disc.point_weight.size(); ++g)
    points_of[r.cell_rank[r.disc.point_cell[g]]].push_back(std::int32_t(g));
  // nodal integration: the face points of each rank's points (on either side)
  const DualFaces& faces = r.disc.faces;
  std::vector<std::vector<std::int32_t>> faces_of(r.ranks);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const int a = r.cell_rank[r.disc.point_cell[faces.plus[f]]];
    faces_of[a].push_back(std::int32_t(f));
    if (faces.minus[f] >= 0 && r.cell_rank[r.disc.point_cell[faces.minus[f]]] != a)
      faces_of[r.cell_rank[r.disc.point_cell[faces.minus[f]]]].push_back(std::int32_t(f));
  }

  // Local particles of each rank: the cells' nodes, the supports of its points and of its owned
  // particles.
  std::vector<std::vector<std::int32_t>> local(r.ranks);
  for (int q = 0; q < r.ranks; ++q) {
    LocalParticleRequest request{grid, r.mesh.X.data(), {}, {}, {}, {}};
    for (auto c : cells_of[q])
      request.cell_nodes.insert(request.cell_nodes.end(), &r.mesh.cell_nodes[r.mesh.cell_offsets[c]],
                                &r.mesh.cell_nodes[r.mesh.cell_offsets[c + 1]]);
    std::int64_t last_cell = -1;
    for (auto g : points_of[q]) {  // one search per cell (its points are contiguous)
      if (r.disc.point_cell[g] != last_cell)
        request.point_groups.push_back(std::int32_t(request.points.size() / 3)), last_cell = r.disc.point_cell[g];
      request.points.insert(request.points.end(), &r.disc.point_X[3 * g], &r.disc.point_X[3 * g] + 3);
    }
    request.point_groups.push_back(std::int32_t(request.points.size() / 3));
    for (auto f : faces_of[q]) request.points.insert(request.points.end(), &faces.X[3 * f], &faces.X[3 * f] + 3);
    for (std::size_t I = 0; I < n; ++I)
      if (owner[I] == q) request.owned.push_back(std::int32_t(I));
    local[q] = local_particles(request);
  }

  const BoundaryFaces boundary = boundary_faces(r.mesh);
  std::vector<Subdomain> subs(r.ranks);
  std::vector<std::int32_t> local_index(n, -1);
  // the partition's own mark, the same in every rank file of this prep (shared/subdomain.hpp)
  const std::string partition = fnv1a_hex(
      r.scene_hash + std::string(reinterpret_cast<const char*>(r.cell_rank.data()), r.cell_rank.size() * sizeof(std::int32_t)));
  for (int q = 0; q < r.ranks; ++q) {
    Subdomain& s = subs[q];
    s.rank = q;
    s.ranks = r.ranks;
    s.scene_hash = r.scene_hash;
    s.partition_hash = partition;
    s.dies = r.dies;
    for (std::size_t k = 0; k < local[q].size(); ++k) {
      const auto I = local[q][k];
      local_index[I] = std::int32_t(k);
      s.global_id.push_back(I);
      s.X.insert(s.X.end(), &r.mesh.X[3 * I], &r.mesh.X[3 * I] + 3);
      s.volume.push_back(r.disc.volume[I]);
      s.spacing.push_back(r.disc.spacing[I]);
      s.owner.push_back(owner[I]);
      const int body = r.mesh.body.empty() ? 0 : r.mesh.body[I];
      s.flags.push_back(std::uint8_t((r.mesh.surface[I] ? kSurface : 0) | (body << kBodyShift)));
    }
    std::vector<std::int32_t> cell_local(nc, -1);
    s.cell_node_offsets.push_back(0);
    for (auto c : cells_of[q]) {
      cell_local[c] = std::int32_t(s.cell_global_id.size());
      s.cell_global_id.push_back(c);
      for (auto k = r.mesh.cell_offsets[c]; k < r.mesh.cell_offsets[c + 1]; ++k)
        s.cell_nodes.push_back(local_index[r.mesh.cell_nodes[k]]);
      s.cell_node_offsets.push_back(std::int32_t(s.cell_nodes.size()));
    }
    for (std::size_t f = 0; f < boundary.size(); ++f)  // a boundary face goes with its cell
      if (r.cell_rank[boundary.cell[f]] == q) {
        for (auto k = boundary.face_offsets[f]; k < boundary.face_offsets[f + 1]; ++k)
          s.surface_face_nodes.push_back(local_index[boundary.face_nodes[k]]);
        s.surface_face_offsets.push_back(std::int32_t(s.surface_face_nodes.size()));
        s.surface_face_cell.push_back(cell_local[boundary.cell[f]]);
      }
    std::vector<std::int32_t> point_local(r.disc.point_weight.size(), -1);
    for (auto g : points_of[q]) {
      point_local[g] = std::int32_t(s.point_weight.size());
      s.point_X.insert(s.point_X.end(), &r.disc.point_X[3 * g], &r.disc.point_X[3 * g] + 3);
      s.point_weight.push_back(r.disc.point_weight[g]);
      s.point_cell.push_back(cell_local[r.disc.point_cell[g]]);
    }
    for (auto f : faces_of[q]) {  // this rank's point first: a face whose plus is elsewhere turns round
      const std::int32_t plus = point_local[faces.plus[f]], minus = faces.minus[f] < 0 ? -1 : point_local[faces.minus[f]];
      const double sign = plus >= 0 ? 1.0 : -1.0;
      s.face_plus.push_back(plus >= 0 ? plus : minus);
      s.face_minus.push_back(plus >= 0 ? minus : -1);
      s.face_X.insert(s.face_X.end(), &faces.X[3 * f], &faces.X[3 * f] + 3);
      for (int i = 0; i < 3; ++i) s.face_nA.push_back(sign * faces.nA[3 * f + i]);
    }
    overlap_maps(local, q, s.neighbour_ranks, s.overlap);
  }
  return subs;
}

nlohmann::json partition_report(const std::vector<Subdomain>& subs, std::size_t particles) {
  nlohmann::json ranks = nlohmann::json::array();
  std::size_t max_points = 0, sum_points = 0, sum_local = 0, values = 0;
  for (const auto& s : subs) {
    std::size_t owned = 0, exchanged = 0;
    for (auto o : s.owner) owned += o == s.rank;
    for (const auto& m : s.overlap) exchanged += 3 * m.size();
    max_points = std::max(max_points, s.point_count());
    sum_points += s.point_count();
    sum_local += s.particle_count();
    values += exchanged;
    ranks.push_back({{"rank", s.rank},
                     {"cells", s.cell_count()},
                     {"integration_points", s.point_count()},
                     {"owned_particles", owned},
                     {"overlap_particles", s.particle_count() - owned},
                     {"neighbour_ranks", s.neighbour_ranks},
                     {"values_exchanged_per_step", exchanged}});
  }
  const double mean = double(sum_points) / double(subs.size());
  return {{"ranks", ranks},
          {"imbalance", mean > 0 ? double(max_points) / mean : 1.0},
          {"overlap_fraction", particles ? double(sum_local - particles) / double(particles) : 0.0},
          {"values_exchanged_per_step", values},
          {"bytes_exchanged_per_step", values * 8}};  // forces travel as 64-bit fixed point
}

}  // namespace rk
