#include "cad_mesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <array>
#include <map>
#include <sstream>
#include <unordered_map>

#include "checked_int.hpp"
#include "discretize.hpp"
#include "cad_format.hpp"
#include "error.hpp"
#include "gmsh_session.hpp"
#include "process_memory.hpp"
#include "stl_check.hpp"

namespace rk {

namespace {

constexpr double kPrepBytesPerParticle = 1.2e3;
constexpr double kNodesPerCube = 1.3;  // particles per volume spacing^3 in a fine mesh (check_size)

// A part whose size in spacings is absurd was almost always given in another unit (a part in mm
// read as metres is 1000x too big): refuse it before meshing, naming the size and the unit.
void check_size(const MeshRequest& r) {
  double lo[3], hi[3];
  gmsh::model::getBoundingBox(-1, -1, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  double extent = 0;  // largest side of the box, metres
  for (int d = 0; d < 3; ++d) extent = std::max(extent, (hi[d] - lo[d]) * r.unit);
  const double across = extent / r.spacing;
  if (across > 5000 || across < 2) {
    std::ostringstream s;
    s << r.cad << ": the part is " << extent << " m across with geometry.unit = " << r.unit
      << " m per CAD unit, which is " << across << " particle spacings of " << r.spacing
      << " m; check geometry.unit (and discretization.spacing)";
    throw Error(s.str());
  }
  // and one that would not fit this machine's memory (too fine a spacing, or a size within the bound above
  // in another unit): the particles from the solid's volume (OpenCASCADE's; the bounding box's where the
  // kernel gives none), at prep's measured 1.2 kB a particle (1.07M particles: 1243 MiB, 2026-12-07)
  double volume = 0;  // m^3
  try {
    gmsh::vectorpair solids;
    gmsh::model::getEntities(solids, 3);
    for (auto [dim, tag] : solids) {
      double v = 0;
      gmsh::model::occ::getMass(dim, tag, v);
      volume += v * r.unit * r.unit * r.unit;
    }
  } catch (...) {  // (gmsh 4.8 throws std::string: a solid of the built-in kernel)
    volume = 0;
  }
  // (the box holds more than the solid: a ring 1.7x, a thin STL shell 10x; refused past 4x the memory then)
  const bool boxed = !(volume > 0);
  if (boxed) volume = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]) * r.unit * r.unit * r.unit;
  // (a mesh holds more nodes than volume / h^3: the STEP billet 3.8x at 1 mm, 20 spacings across, and 1.3x at
  // 0.6 mm, measured 2026-12-08; the bound takes the fine meshes' 1.3, where the memory is)
  const double particles = kNodesPerCube * volume / (r.spacing * r.spacing * r.spacing),
               need_mb = particles * kPrepBytesPerParticle / 1048576;
  const double available_mb = available_memory_mb();
  if (available_mb > 0 && need_mb > (boxed ? 4 : 1) * available_mb) {
    std::ostringstream s;
    s.precision(3);
    s << r.cad << ": at discretization.spacing = " << r.spacing << " m the part (" << volume
      << (boxed ? " m^3 at most, its bounding box," : " m^3") << " with geometry.unit = " << r.unit << " m per CAD unit) takes about " << particles
      << " particles, whose preparation needs about " << need_mb / 1024 << " GiB, more than the "
      << available_mb / 1024 << " GiB this machine has available; check geometry.unit and discretization.spacing";
    throw Error(s.str());
  }
}

double distance(const VolumeMesh& mesh, std::size_t I, std::size_t J) {
  double r2 = 0;
  for (std::size_t i = 0; i < 3; ++i) r2 += (mesh.X[3 * I + i] - mesh.X[3 * J + i]) * (mesh.X[3 * I + i] - mesh.X[3 * J + i]);
  return std::sqrt(r2);
}

template <class Reach>
std::array<std::size_t, 2> near_pair(const VolumeMesh& mesh, const std::vector<int>& group, double bin_side, Reach reach);

// Solids of one file that do not touch but lie within the shape functions' reach of each other would be
// tied across the gap as if joined (two 10 mm boxes 1 mm apart at 2.5 mm spacing: the one no die touched
// took a plastic strain of 0.19 from its neighbour's upsetting). Refused, naming the gap. Solids that touch
// (sharing nodes, or nodes within 1e-6 of the largest spacing) are one part.
void check_solids_apart(const VolumeMesh& mesh, std::vector<int> group, const MeshRequest& r, std::size_t solids) {
  const std::vector<double> h = node_spacing(mesh);  // as the supports will take it (discretize)
  const double h_max = *std::max_element(h.begin(), h.end()), touching = 1e-6 * h_max;
  for (;;) {  // touching solids joined: the first pair within a hair of each other, until none is left
    const auto [I, J] = near_pair(mesh, group, r.dilation * h_max, [&](std::size_t, std::size_t) { return touching; });
    if (I == mesh.node_count()) break;
    const int from = group[J], to = group[I];
    for (int& g : group)
      if (g == from) g = to;
  }
  const auto reach = [&](std::size_t I, std::size_t J) { return r.dilation * std::max(h[I], h[J]); };
  const auto [I, J] = near_pair(mesh, group, r.dilation * h_max, reach);
  if (I == mesh.node_count()) return;
  const double gap = distance(mesh, I, J);
  std::ostringstream s;
  s << r.cad << ": holds " << solids << " solids, two of them " << gap << " m apart at (" << mesh.X[3 * I] << ", "
    << mesh.X[3 * I + 1] << ", " << mesh.X[3 * I + 2] << ") m, within the shape functions' reach there (discretization.dilation "
    << "x the particles' spacing = " << reach(I, J) << " m): the part's supports would tie them across the gap as if joined; "
    << (gap >= 0.75 * r.spacing ? "give the second solid a file of its own under geometry.bodies (a body's supports stop at "
                                  "its surface), or join them"
                                : "join them (fuse the solids, or mesh them conformally: Coherence in a .geo), or move them "
                                  "at least 0.75 discretization.spacing apart and give the second a file of its own under "
                                  "geometry.bodies");
  throw Error(s.str());
}

// CAD without a script of its own (STEP, IGES, BREP, STL) is meshed in tetrahedra of 2 h to 3 h,
// each split into four hexahedra (whose edges run from a half to a sixth of the tetrahedron's): the
// median cell edge then lands near h (a 20 x 10 x 10 mm STEP box: 0.59 / 0.76 / 1.08 h at h = 2.5 / 1
// / 0.5 mm; a 10 mm STL cube 0.55 / 0.70 / 1.08 h at 2 / 1 / 0.5 mm; measured 2026-12-02). With the
// minimum at h / 2, as before, gmsh meshed far finer than asked (0.31 h on the cube at 2 mm, and the
// same 5607 particles at any spacing).
void set_tet_size(double h) {
  gmsh::option::setNumber("Mesh.MeshSizeMax", 3 * h);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 2 * h);
  gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 2);  // all hexahedra
}

VolumeMesh mesh_with_gmsh(const MeshRequest& r) {
  const std::string ext = lower_extension(r.cad);
  const double h = r.spacing / r.unit;  // in CAD units
  GmshSession session(h);
  if (ext == ".geo") {
    gmsh::open(r.cad);
  } else if (declares_its_unit(ext) || ext == ".brep") {
    gmsh::merge(r.cad);
    gmsh::vectorpair solids;
    gmsh::model::getEntities(solids, 3);
    if (solids.size() > 1) {  // solids that touch meshed alike along the faces they share: one part (and
      gmsh::vectorpair pieces;  // overlapping ones split into pieces that do not overlap, not counted twice)
      std::vector<gmsh::vectorpair> of;
      gmsh::model::occ::fragment(solids, {}, pieces, of);
      gmsh::model::occ::synchronize();
    }
    set_tet_size(h);
  } else if (ext == ".stl") {
    check_stl_solid(r.cad);
    gmsh::merge(r.cad);
    gmsh::model::mesh::classifySurfaces(M_PI / 4, true, false, M_PI);  // STL facets -> surfaces
    gmsh::model::mesh::createGeometry();
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    std::vector<int> tags;
    for (auto [dim, tag] : surfaces) tags.push_back(tag);
    gmsh::model::geo::addVolume({gmsh::model::geo::addSurfaceLoop(tags)});
    gmsh::model::geo::synchronize();
    set_tet_size(h);
  } else {
    throw Error(r.cad + ": unsupported CAD format '" + ext + "' (use .geo, .step, .iges, .brep or .stl)");
  }
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  if (volumes.empty()) {
    std::string why = GmshSession::errors();
    throw Error(r.cad + ": the CAD holds no closed solid (no volume to mesh)" + (why.empty() ? "" : ": " + why));
  }
  check_size(r);
  gmsh::model::mesh::generate(3);

  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, 3, -1);
  VolumeMesh mesh;
  std::unordered_map<std::size_t, std::int32_t> index;  // gmsh node tag -> node index
  std::vector<std::size_t> order;                       // node index -> gmsh tag
  for (std::size_t t = 0; t < types.size(); ++t) {
    int per;
    if (types[t] == 5) per = 8;
    else if (types[t] == 4) per = 4;
    else
      throw Error(r.cad + ": the mesh has elements of gmsh type " + std::to_string(types[t]) +
                  "; only hexahedra and tetrahedra are integration cells");
    for (std::size_t e = 0; e < tags[t].size(); ++e) {
      for (int a = 0; a < per; ++a) {
        auto tag = nodes[t][e * per + a];
        auto [it, fresh] = index.emplace(tag, std::int32_t(order.size()));
        if (fresh) order.push_back(tag);
        mesh.cell_nodes.push_back(it->second);
      }
      mesh.cell_offsets.push_back(std::int32_t(mesh.cell_nodes.size()));
    }
  }
  // 32-bit offsets and METIS's 32-bit indices: the last offset fits only if every one does
  checked_int(std::int64_t(mesh.cell_nodes.size()), r.cad + ": the mesh's cell-node entries");
  if (mesh.cell_count() == 0) throw Error(r.cad + ": meshing produced no 3-D cells (open surface or zero volume?)");

  mesh.X.resize(3 * order.size());
  mesh.surface.assign(order.size(), 0);
  {
    std::vector<std::size_t> all;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(all, coord, param, -1, -1, true, false);
    std::vector<std::uint8_t> placed(order.size(), 0);
    for (std::size_t k = 0; k < all.size(); ++k) {
      auto it = index.find(all[k]);
      if (it == index.end()) continue;
      for (int d = 0; d < 3; ++d) mesh.X[3 * it->second + d] = coord[3 * k + d] * r.unit;
      placed[std::size_t(it->second)] = 1;
    }
    // A volume mesh of a faceted (STL) surface can come back with nodes gmsh never placed or placed far
    // outside the part (a closed STL cylinder at 1.9 mm: nodes at 1e17 m among its 3953): refused by name.
    // Outside: beyond the box of the middle 98 % of the nodes by ten times its size (gmsh's own boxes of an
    // STL's entities hold those nodes too)
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      std::vector<double> c(order.size());
      for (std::size_t I = 0; I < order.size(); ++I) c[I] = mesh.X[3 * I + std::size_t(d)];
      const auto at = [&](double q) {
        auto it = c.begin() + std::ptrdiff_t(q * double(c.size() - 1));
        std::nth_element(c.begin(), it, c.end());
        return *it;
      };
      const double a = at(0.01), b = at(0.99);
      lo[d] = a - 10 * (b - a) - r.spacing, hi[d] = b + 10 * (b - a) + r.spacing;
    }
    for (std::size_t I = 0; I < order.size(); ++I) {
      bool inside = placed[I] != 0;
      for (int d = 0; d < 3 && inside; ++d) inside = mesh.X[3 * I + std::size_t(d)] >= lo[d] && mesh.X[3 * I + std::size_t(d)] <= hi[d];
      if (!inside) {
        std::ostringstream s;
        s << r.cad << ": gmsh's volume mesh at discretization.spacing = " << r.spacing << " m has a node "
          << (placed[I] ? "far outside the part" : "without coordinates")
          << " (its meshing of this surface failed); another spacing, or for an STL a finer faceting or the STEP, may mesh";
        throw Error(s.str());
      }
    }
  }
  // Surface nodes: nodes of the 2-D elements on the volumes' boundaries.
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary(volumes, boundary, true, false, false);
  for (auto [dim, tag] : boundary) {
    std::vector<std::size_t> ntags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(ntags, coord, param, dim, std::abs(tag), true, false);
    for (auto n : ntags) {
      auto it = index.find(n);
      if (it != index.end()) mesh.surface[it->second] = 1;
    }
  }
  if (volumes.size() > 1 && r.dilation > 0) {  // each node's solid; solids that share a node touch: one group
    std::vector<int> solid(mesh.node_count(), -1), group(volumes.size());
    for (std::size_t v = 0; v < volumes.size(); ++v) group[v] = int(v);
    for (std::size_t v = 0; v < volumes.size(); ++v) {
      std::vector<std::size_t> ntags;
      std::vector<double> coord, param;
      gmsh::model::mesh::getNodes(ntags, coord, param, 3, volumes[v].second, true, false);
      for (auto n : ntags) {
        auto it = index.find(n);
        if (it == index.end()) continue;
        int& s = solid[std::size_t(it->second)];
        if (const int from = s >= 0 ? group[std::size_t(s)] : -1, to = group[v]; s >= 0 && from != to)
          for (int& g : group)  // (the other group relabelled as this one)
            if (g == from) g = to;
        s = int(v);
      }
    }
    for (int& s : solid) s = s < 0 ? 0 : group[std::size_t(s)];
    check_solids_apart(mesh, solid, r, volumes.size());
  }
  return mesh;
}

}  // namespace

VolumeMesh mesh_cad(const MeshRequest& r) {
  require_file(r.cad, "CAD file");
  try {
    return mesh_with_gmsh(r);
  } catch (const std::string& e) {  // gmsh 4.8 throws std::string
    throw Error(r.cad + ": gmsh failed: " + e);
  }
}

const std::vector<std::vector<int>>& cell_faces(int nodes_per_cell) {
  static const std::vector<std::vector<int>> hex{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  static const std::vector<std::vector<int>> tet{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return nodes_per_cell == 8 ? hex : tet;
}

std::vector<std::vector<std::uint8_t>> boundary_face_flags(const VolumeMesh& mesh) {
  struct Key {
    std::array<std::int32_t, 4> nodes;
    std::int32_t cell, face;
  };
  std::vector<Key> keys;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int32_t* nodes = &mesh.cell_nodes[mesh.cell_offsets[c]];
    const auto& faces = cell_faces(mesh.cell_offsets[c + 1] - mesh.cell_offsets[c]);
    for (std::size_t k = 0; k < faces.size(); ++k) {
      Key key{{-1, -1, -1, -1}, std::int32_t(c), std::int32_t(k)};
      for (std::size_t a = 0; a < faces[k].size(); ++a) key.nodes[a] = nodes[faces[k][a]];
      std::sort(key.nodes.begin(), key.nodes.end());
      keys.push_back(key);
    }
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) { return a.nodes < b.nodes; });
  std::vector<std::vector<std::uint8_t>> boundary(mesh.cell_count());
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    boundary[c].assign(cell_faces(mesh.cell_offsets[c + 1] - mesh.cell_offsets[c]).size(), 0);
  for (std::size_t k = 0; k < keys.size();) {
    std::size_t e = k + 1;
    while (e < keys.size() && keys[e].nodes == keys[k].nodes) ++e;
    if (e - k == 1) boundary[keys[k].cell][keys[k].face] = 1;
    k = e;
  }
  return boundary;
}

BoundaryFaces boundary_faces(const VolumeMesh& mesh) {
  const auto flags = boundary_face_flags(mesh);
  BoundaryFaces out;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int32_t* n = &mesh.cell_nodes[std::size_t(mesh.cell_offsets[c])];
    const int count = mesh.cell_offsets[c + 1] - mesh.cell_offsets[c];
    const auto& faces = cell_faces(count);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (!flags[c][f]) continue;
      std::vector<std::int32_t> nodes;
      for (int a : faces[f]) nodes.push_back(n[a]);
      // outward: the face's normal points away from the cell's centre (whatever the cell's handedness)
      double centre[3] = {0, 0, 0}, mid[3] = {0, 0, 0}, normal[3] = {0, 0, 0};
      for (int a = 0; a < count; ++a)
        for (int i = 0; i < 3; ++i) centre[i] += mesh.X[3 * std::size_t(n[a]) + i] / count;
      for (std::size_t a = 0; a < nodes.size(); ++a) {
        const double* p = &mesh.X[3 * std::size_t(nodes[a])];
        const double* q = &mesh.X[3 * std::size_t(nodes[(a + 1) % nodes.size()])];
        for (int i = 0; i < 3; ++i) mid[i] += p[i] / double(nodes.size());
        normal[0] += p[1] * q[2] - p[2] * q[1], normal[1] += p[2] * q[0] - p[0] * q[2], normal[2] += p[0] * q[1] - p[1] * q[0];
      }
      double side = 0;
      for (int i = 0; i < 3; ++i) side += normal[i] * (mid[i] - centre[i]);
      if (side < 0) std::reverse(nodes.begin(), nodes.end());
      out.face_nodes.insert(out.face_nodes.end(), nodes.begin(), nodes.end());
      out.face_offsets.push_back(std::int32_t(out.face_nodes.size()));
      out.cell.push_back(std::int32_t(c));
    }
  }
  checked_int(std::int64_t(out.face_nodes.size()), "the mesh's boundary-face node entries");
  return out;
}

double median_edge(const VolumeMesh& mesh) {
  static const int hex[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  static const int tet[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  std::vector<double> edges;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int32_t* n = &mesh.cell_nodes[std::size_t(mesh.cell_offsets[c])];
    const bool is_hex = mesh.cell_offsets[c + 1] - mesh.cell_offsets[c] == 8;
    for (int e = 0; e < (is_hex ? 12 : 6); ++e) {
      const int a = is_hex ? hex[e][0] : tet[e][0], b = is_hex ? hex[e][1] : tet[e][1];
      double d2 = 0;
      for (int i = 0; i < 3; ++i) {
        const double d = mesh.X[3 * std::size_t(n[a]) + i] - mesh.X[3 * std::size_t(n[b]) + i];
        d2 += d * d;
      }
      edges.push_back(std::sqrt(d2));
    }
  }
  if (edges.empty()) return 0;
  std::nth_element(edges.begin(), edges.begin() + std::ptrdiff_t(edges.size() / 2), edges.end());
  return edges[edges.size() / 2];
}

}  // namespace rk

namespace rk {

void append_body(VolumeMesh& mesh, const VolumeMesh& other, int body) {
  const auto offset = std::int32_t(mesh.node_count());
  mesh.body.resize(mesh.node_count(), 0);
  mesh.X.insert(mesh.X.end(), other.X.begin(), other.X.end());
  mesh.surface.insert(mesh.surface.end(), other.surface.begin(), other.surface.end());
  mesh.body.resize(mesh.node_count(), std::uint8_t(body));
  const std::int32_t cells0 = mesh.cell_offsets.back();
  for (std::size_t c = 1; c < other.cell_offsets.size(); ++c) mesh.cell_offsets.push_back(cells0 + other.cell_offsets[c]);
  for (auto node : other.cell_nodes) mesh.cell_nodes.push_back(node + offset);
}

namespace {

// The closest two surface nodes of different groups (group[J] > group[I]) of those closer than reach(I, J) <=
// bin_side, by bins of that side; {n, n} (n the node count) where there are none
template <class Reach>
std::array<std::size_t, 2> near_pair(const VolumeMesh& mesh, const std::vector<int>& group, double bin_side, Reach reach) {
  std::map<std::array<std::int64_t, 3>, std::vector<std::size_t>> bins;
  auto bin = [&](std::size_t I, int d) { return std::int64_t(std::floor(mesh.X[3 * I + std::size_t(d)] / bin_side)); };
  std::array<std::size_t, 2> pair{mesh.node_count(), mesh.node_count()};
  double closest = HUGE_VAL;
  for (std::size_t I = 0; I < mesh.node_count(); ++I)
    if (mesh.surface[I]) bins[{bin(I, 0), bin(I, 1), bin(I, 2)}].push_back(I);
  for (std::size_t I = 0; I < mesh.node_count(); ++I) {
    if (!mesh.surface[I]) continue;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c) {
          auto it = bins.find({bin(I, 0) + a, bin(I, 1) + b, bin(I, 2) + c});
          if (it == bins.end()) continue;
          for (std::size_t J : it->second)
            if (const double r = distance(mesh, I, J); group[J] > group[I] && r < reach(I, J) && r < closest)
              closest = r, pair = {I, J};
        }
  }
  return pair;
}

}  // namespace

void check_bodies_apart(const VolumeMesh& mesh, const std::vector<std::string>& names, double spacing) {
  if (mesh.body.empty()) return;
  const double reach = 0.75 * spacing;
  const auto [I, J] = near_pair(mesh, std::vector<int>(mesh.body.begin(), mesh.body.end()), reach,
                                [&](std::size_t, std::size_t) { return reach; });
  if (I == mesh.node_count()) return;
  std::ostringstream s;
  s << "geometry.bodies: '" << names[mesh.body[J]] << "' starts " << distance(mesh, I, J) << " m from '" << names[mesh.body[I]]
    << "' at (" << mesh.X[3 * I] << ", " << mesh.X[3 * I + 1] << ", " << mesh.X[3 * I + 2]
    << ") m; bodies must start at least 0.75 discretization.spacing (" << reach
    << " m) apart, where their contact begins (a body inside another, or touching it, would be thrown off at the first step)";
  throw Error(s.str());
}

}  // namespace rk
