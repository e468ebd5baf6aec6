#include "subdomain.hpp"

#include <cmath>
#include <cstdio>

#include <fstream>

#include "error.hpp"
#include "h5file.hpp"
#include "hash.hpp"
#include "text_file.hpp"

namespace rk {

std::string subdomain_path(const std::string& case_dir, int rank) {
  char name[32];
  std::snprintf(name, sizeof name, "rank_%04d.h5", rank);
  return case_dir + "/sub/" + name;
}

std::string subdomain_hash_path(const std::string& path) { return path + ".fnv1a"; }

void write_subdomain(const std::string& path, const Subdomain& s) {
  write_subdomain_file(path, s);
  write_text_file(subdomain_hash_path(path), file_hash(path) + "\n");
}

void write_subdomain_file(const std::string& path, const Subdomain& s) {
  H5File f(path, H5File::Mode::create);
  f.set_attr("format_version", kFormatVersion);
  f.set_attr("rank", s.rank);
  f.set_attr("ranks", s.ranks);
  f.set_attr("scene_hash", s.scene_hash);
  f.set_attr("partition_hash", s.partition_hash);
  f.set_attr("units", std::string("SI"));
  f.write("particles/global_id", s.global_id);
  f.write("particles/X", s.X, 3);
  f.write("particles/volume", s.volume);
  f.write("particles/spacing", s.spacing);
  f.write("particles/owner", s.owner);
  f.write("particles/flags", s.flags);
  f.write("cells/global_id", s.cell_global_id);
  f.write("cells/node_offsets", s.cell_node_offsets);
  f.write("cells/nodes", s.cell_nodes);
  f.write("points/X", s.point_X, 3);
  f.write("points/weight", s.point_weight);
  f.write("points/cell", s.point_cell);
  if (s.face_count() > 0) {
    f.write("faces/X", s.face_X, 3);
    f.write("faces/nA", s.face_nA, 3);
    f.write("faces/plus", s.face_plus);
    f.write("faces/minus", s.face_minus);
  }
  f.write("surface/face_offsets", s.surface_face_offsets);
  f.write("surface/face_nodes", s.surface_face_nodes);
  f.write("surface/face_cell", s.surface_face_cell);
  f.write("overlap/ranks", s.neighbour_ranks);
  for (std::size_t k = 0; k < s.neighbour_ranks.size(); ++k) {
    char name[40];
    std::snprintf(name, sizeof name, "overlap/rank_%04d", s.neighbour_ranks[k]);
    f.write(name, s.overlap[k]);
  }
  f.set_attr("die_count", std::int64_t(s.dies.size()));
  for (std::size_t k = 0; k < s.dies.size(); ++k) {
    char name[40];
    std::snprintf(name, sizeof name, "dies/%04zu/", k);
    f.write(std::string(name) + "vertices", s.dies[k].vertices, 3);
    f.write(std::string(name) + "triangles", s.dies[k].triangles, 3);
  }
  f.close();
}

namespace {
void require(bool ok, const std::string& path, const std::string& what) {
  if (!ok) throw Error(path + ": " + what);
}
}  // namespace

Subdomain read_subdomain(const std::string& path, int rank, int ranks, const std::string& scene_hash) {
  // The whole-file hash is checked before HDF5 parses a byte: libhdf5 is not safe on corrupt files.
  if (!std::ifstream(path)) throw Error(path + ": file not found");
  std::ifstream sidecar(subdomain_hash_path(path));
  std::string expected;
  if (!(sidecar >> expected)) {
    throw Error(subdomain_hash_path(path) + ": checksum file missing; re-run rkprep");
  }
  if (file_hash(path) != expected)
    throw Error(path + ": checksum mismatch: the file is corrupt or truncated, or not the file its .fnv1a was written for; re-run rkprep");
  H5File f(path, H5File::Mode::read);
  Subdomain s;
  const auto version = f.attr_int("format_version");
  require(version == kFormatVersion, path,
          "format version " + std::to_string(version) + " is not the version this program reads (" +
              std::to_string(kFormatVersion) + "); re-run rkprep");
  s.rank = f.attr_int("rank");
  s.ranks = f.attr_int("ranks");
  s.scene_hash = f.attr_string("scene_hash");
  if (f.has_attr("partition_hash")) s.partition_hash = f.attr_string("partition_hash");
  require(s.ranks == ranks, path,
          "prepared for " + std::to_string(s.ranks) + " ranks but the job has " + std::to_string(ranks) +
              "; re-run rkprep --ranks " + std::to_string(ranks) + " or mpirun -np " + std::to_string(s.ranks));
  require(s.rank == rank, path, "belongs to rank " + std::to_string(s.rank) + ", not rank " + std::to_string(rank));
  require(scene_hash.empty() || s.scene_hash == scene_hash, path,
          "was prepared from another scene (hash " + s.scene_hash + ", scene.resolved.yaml gives " + scene_hash +
              "); re-run rkprep");

  s.global_id = f.read<std::int64_t>("particles/global_id");
  s.X = f.read<double>("particles/X", 3);
  s.volume = f.read<double>("particles/volume");
  s.spacing = f.read<double>("particles/spacing");
  s.owner = f.read<std::int32_t>("particles/owner");
  s.flags = f.read<std::uint8_t>("particles/flags");
  s.cell_global_id = f.read<std::int64_t>("cells/global_id");
  s.cell_node_offsets = f.read<std::int32_t>("cells/node_offsets");
  s.cell_nodes = f.read<std::int32_t>("cells/nodes");
  s.point_X = f.read<double>("points/X", 3);
  s.point_weight = f.read<double>("points/weight");
  s.point_cell = f.read<std::int32_t>("points/cell");
  if (f.exists("faces")) {
    s.face_X = f.read<double>("faces/X", 3);
    s.face_nA = f.read<double>("faces/nA", 3);
    s.face_plus = f.read<std::int32_t>("faces/plus");
    s.face_minus = f.read<std::int32_t>("faces/minus");
  }
  s.surface_face_offsets = f.read<std::int32_t>("surface/face_offsets");
  s.surface_face_nodes = f.read<std::int32_t>("surface/face_nodes");
  s.surface_face_cell = f.read<std::int32_t>("surface/face_cell");
  s.neighbour_ranks = f.read<std::int32_t>("overlap/ranks");
  for (auto q : s.neighbour_ranks) {
    char name[40];
    std::snprintf(name, sizeof name, "overlap/rank_%04d", q);
    s.overlap.push_back(f.read<std::int32_t>(name));
  }

  const auto die_count = f.attr_int("die_count");
  for (std::int64_t k = 0; k < die_count; ++k) {
    char name[40];
    std::snprintf(name, sizeof name, "dies/%04lld/", static_cast<long long>(k));
    DieSurface d{f.read<double>(std::string(name) + "vertices", 3), f.read<std::int32_t>(std::string(name) + "triangles", 3)};
    for (auto v : d.triangles)
      require(v >= 0 && std::size_t(v) < d.vertices.size() / 3, path, "die " + std::to_string(k) + " has a bad triangle");
    s.dies.push_back(std::move(d));
  }

  const std::size_t n = s.global_id.size(), c = s.cell_global_id.size(), m = s.point_weight.size();
  require(s.X.size() == 3 * n && s.volume.size() == n && s.spacing.size() == n && s.owner.size() == n &&
              s.flags.size() == n,
          path, "particle datasets disagree on the particle count");
  require(s.cell_node_offsets.size() == c + 1 && s.point_X.size() == 3 * m && s.point_cell.size() == m, path,
          "cell or point datasets disagree on their counts");
  require(c == 0 || std::size_t(s.cell_node_offsets.back()) == s.cell_nodes.size(), path,
          "cell node offsets disagree with the node list");
  for (std::size_t i = 0; i < n; ++i) {
    require(std::isfinite(s.X[3 * i]) && std::isfinite(s.X[3 * i + 1]) && std::isfinite(s.X[3 * i + 2]) &&
                s.volume[i] > 0 && s.spacing[i] > 0,
            path, "particle " + std::to_string(s.global_id[i]) + " has a non-finite position or a non-positive volume");
    require(s.owner[i] >= 0 && s.owner[i] < ranks, path,
            "particle " + std::to_string(s.global_id[i]) + " has an invalid owner rank");
    require(i == 0 || s.global_id[i] > s.global_id[i - 1], path, "particles are not sorted by global id");
  }
  for (auto node : s.cell_nodes) require(node >= 0 && std::size_t(node) < n, path, "a cell node index is out of range");
  for (std::size_t g = 0; g < m; ++g)
    require(s.point_cell[g] >= 0 && std::size_t(s.point_cell[g]) < c && s.point_weight[g] > 0 &&
                std::isfinite(s.point_X[3 * g]),
            path, "integration point " + std::to_string(g) + " has a bad cell index, weight or position");
  const std::size_t nf = s.face_plus.size();
  require(s.face_X.size() == 3 * nf && s.face_nA.size() == 3 * nf && s.face_minus.size() == nf, path,
          "face datasets disagree on their counts");
  for (std::size_t q = 0; q < nf; ++q)
    require(s.face_plus[q] >= 0 && std::size_t(s.face_plus[q]) < m && s.face_minus[q] >= -1 &&
                s.face_minus[q] < std::int64_t(m) && std::isfinite(s.face_X[3 * q]) && std::isfinite(s.face_nA[3 * q]),
            path, "face point " + std::to_string(q) + " has a bad point index or a non-finite position or normal");
  require(!s.surface_face_offsets.empty() && s.surface_face_offsets.front() == 0 &&
              std::size_t(s.surface_face_offsets.back()) == s.surface_face_nodes.size(),
          path, "surface face offsets disagree with the node list");
  for (std::size_t q = 0; q + 1 < s.surface_face_offsets.size(); ++q) {
    const auto count = s.surface_face_offsets[q + 1] - s.surface_face_offsets[q];
    require(count == 3 || count == 4, path, "surface face " + std::to_string(q) + " has neither 3 nor 4 nodes");
  }
  for (auto node : s.surface_face_nodes)
    require(node >= 0 && std::size_t(node) < n, path, "a surface face node index is out of range");
  require(s.surface_face_cell.size() == s.surface_face_count(), path, "surface face cells disagree with the faces' count");
  for (auto cell : s.surface_face_cell)
    require(cell >= 0 && std::size_t(cell) < c, path, "a surface face's cell index is out of range");
  for (const auto& list : s.overlap)
    for (auto i : list) require(i >= 0 && std::size_t(i) < n, path, "an overlap map index is out of range");
  return s;
}

}  // namespace rk
