// The per-rank subdomain file (CASE/sub/rank_NNNN.h5): what one rank needs to run, written by rkprep,
// read by rksolve. Layout (HDF5, every dataset Fletcher32-checksummed):
//   attrs   format_version, rank, ranks, scene_hash, partition_hash, units="SI"
//   particles/{global_id, X[n,3], volume, spacing, owner, flags}      local particles (owned + overlap)
//   cells/{global_id, node_offsets[c+1], nodes}                      integration cells of this rank
//   points/{X[m,3], weight, cell}                                    their integration points
//   faces/{X[f,3], nA[f,3], plus, minus}                             nodal integration only: quadrature
//                                                                    points on the points' smoothing-cell faces
//   surface/{face_offsets[s+1], face_nodes, face_cell}               the part's boundary faces of this
//                                                                    rank's cells, nodes counter-clockwise
//                                                                    seen from outside, and their cells
//   overlap/ranks, overlap/rank_NNNN                                 per neighbour: shared local
//                                                                    particle indices, ascending global id
//   dies/NNNN/{vertices[v,3], triangles[t,3]}  (attr die_count)      rigid die surfaces, outward
//                                                                    normals (every rank holds all)
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace rk {

inline constexpr std::int64_t kFormatVersion = 4;

// particles/flags: bit 0 the surface; bits 1-7 the body the particle belongs to (0: the part's
// geometry.cad, then the scene's bodies in order)
enum ParticleFlag : std::uint8_t { kSurface = 1 };
inline constexpr int kBodyShift = 1;
inline int body_of(std::uint8_t flags) { return flags >> kBodyShift; }

struct DieSurface {
  std::vector<double> vertices;        // 3 per vertex, m, reference (t = 0) position
  std::vector<std::int32_t> triangles; // 3 vertex indices each, counter-clockwise seen from outside

  std::size_t triangle_count() const { return triangles.size() / 3; }
  const double* corner(std::size_t t, int k) const { return &vertices[3 * std::size_t(triangles[3 * t + std::size_t(k)])]; }
  // Triangle t's (b - a) x (c - a): the outward normal times twice its area; returns the area
  double area_normal(std::size_t t, double n[3]) const {
    const double *a = corner(t, 0), *b = corner(t, 1), *c = corner(t, 2);
    double e1[3], e2[3];
    for (int i = 0; i < 3; ++i) e1[i] = b[i] - a[i], e2[i] = c[i] - a[i];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  void centre(std::size_t t, double c[3]) const {
    for (int i = 0; i < 3; ++i) c[i] = (corner(t, 0)[i] + corner(t, 1)[i] + corner(t, 2)[i]) / 3;
  }
};

struct Subdomain {
  std::int64_t rank = 0, ranks = 1;
  std::string scene_hash;
  // the partition's (a hash of the scene's and the cells' ranks): every rank file of one rkprep run holds
  // the same, so rksolve refuses files of two preps (another --partitioner) mixed in one case ("" in
  // files written before it, which are not checked)
  std::string partition_hash;

  // Local particles, sorted by global id.
  std::vector<std::int64_t> global_id;
  std::vector<double> X;        // reference position, 3 per particle (m)
  std::vector<double> volume;   // m^3, consistent with the cell volumes
  std::vector<double> spacing;  // local particle spacing h_I (m); support radius = dilation * h_I
  std::vector<std::int32_t> owner;
  std::vector<std::uint8_t> flags;

  // Integration cells (elements of the prep mesh) assigned to this rank, nodes as local indices.
  std::vector<std::int64_t> cell_global_id;
  std::vector<std::int32_t> cell_node_offsets;
  std::vector<std::int32_t> cell_nodes;

  // Integration points of those cells.
  std::vector<double> point_X;       // 3 per point (m)
  std::vector<double> point_weight;  // m^3
  std::vector<std::int32_t> point_cell;

  // Nodal integration only (prep/nodal_integration.hpp): quadrature points on the faces of the
  // points' smoothing cells; each adds +N_I(x) nA to the gradient sum of point face_plus and -N_I(x) nA
  // to that of face_minus (-1: none on this rank, or the domain boundary).
  std::vector<double> face_X, face_nA;  // 3 per face point
  std::vector<std::int32_t> face_plus, face_minus;

  // The part's boundary: the faces of this rank's cells that no other cell shares (CSR, local
  // particle indices, counter-clockwise seen from outside) and the local cell each bounds: heat
  // exchange through the surface, the shear friction of hot forging.
  std::vector<std::int32_t> surface_face_offsets{0}, surface_face_nodes, surface_face_cell;

  // Overlap maps: for neighbour_ranks[k], the shared particles' local indices (ascending global id).
  std::vector<std::int32_t> neighbour_ranks;
  std::vector<std::vector<std::int32_t>> overlap;

  std::vector<DieSurface> dies;  // in the scene's order

  std::size_t particle_count() const { return global_id.size(); }
  std::size_t cell_count() const { return cell_global_id.size(); }
  std::size_t point_count() const { return point_weight.size(); }
  std::size_t face_count() const { return face_plus.size(); }
  std::size_t surface_face_count() const { return surface_face_offsets.size() - 1; }
};

std::string subdomain_path(const std::string& case_dir, int rank);

// Writes the file and its whole-file hash beside it (PATH.fnv1a).
void write_subdomain(const std::string& path, const Subdomain& s);
void write_subdomain_file(const std::string& path, const Subdomain& s);  // the HDF5 file alone
std::string subdomain_hash_path(const std::string& path);

// Reads and checks that the file belongs to this run: whole-file hash (before HDF5 parses it),
// format version, rank, rank count, scene hash, consistent counts and finite coordinates. Any mismatch is an rk::Error naming the file and problem.
Subdomain read_subdomain(const std::string& path, int rank, int ranks, const std::string& scene_hash);

}  // namespace rk
