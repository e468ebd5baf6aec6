#include "boundary/constraints.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "checked_int.hpp"
#include "error.hpp"
#include "model.hpp"
#include "rk/local_shapes.hpp"

namespace rk {
namespace {

// One constraint before orthonormalization: direction, value coef * stroke of prescribed face
// `value_face` (-1: zero), and the face its reaction is reported under (-1: symmetry plane).
struct Candidate {
  Eigen::Vector3d e;
  double coef = 0;
  int value_face = -1;
  int face = -1;
};

std::string where(const Model& md, std::size_t I) {
  std::ostringstream s;
  s << "particle " << md.global_id[I] << " at (" << md.X[3 * I] << ", " << md.X[3 * I + 1] << ", " << md.X[3 * I + 2]
    << ") m";
  return s.str();
}

// Within 1e-6 of the particle's spacing: the mesh coordinates' round-off, far below any spacing.
bool on_plane(const Model& md, std::size_t I, const Vec3& point, const Vec3& normal) {
  double d = 0;
  for (int i = 0; i < 3; ++i) d += (md.X[3 * I + i] - point[i]) * normal[i];
  return std::abs(d) <= 1e-6 * md.spacing[I];
}

// The candidates of particle I in priority order: fixed faces, prescribed faces, symmetry planes;
// `faces` gets the faces it lies on (all_faces numbering).
std::vector<Candidate> candidates(const Model& md, std::size_t I, const Scene& scene, std::vector<std::size_t>& faces) {
  std::vector<Candidate> out;
  faces.clear();
  const int fixed = int(scene.fixed_faces.size()), reported = int(reported_faces(scene));
  for (int f = 0; f < fixed; ++f)
    if (on_plane(md, I, scene.fixed_faces[f].point, scene.fixed_faces[f].normal)) {
      for (int d = 0; d < 3; ++d) out.push_back({Eigen::Vector3d::Unit(d), 0.0, -1, f});
      faces.push_back(std::size_t(f));
    }
  for (int p = 0; p < int(scene.prescribed_faces.size()); ++p) {
    const EssentialFace& face = scene.prescribed_faces[p];
    if (on_plane(md, I, face.point, face.normal)) {
      const Vec3& d = face.motion.direction;
      out.push_back({Eigen::Vector3d(d[0], d[1], d[2]), 1.0, p, fixed + p});
      faces.push_back(std::size_t(fixed + p));
    }
  }
  for (int s = 0; s < int(scene.symmetry_planes.size()); ++s) {
    const SymmetryPlane& pl = scene.symmetry_planes[s];
    if (on_plane(md, I, pl.point, pl.normal)) {
      out.push_back({Eigen::Vector3d(pl.normal[0], pl.normal[1], pl.normal[2]), 0.0, -1, -1});
      faces.push_back(std::size_t(reported + s));
    }
  }
  return out;
}

// Gram-Schmidt on directions and values together: e_k . u = g_k stays the same set of conditions.
std::vector<Candidate> orthonormalize(const Model& md, std::size_t I, std::vector<Candidate> in, const Scene& scene,
                                      const std::vector<std::size_t>& faces) {
  std::vector<Candidate> out;
  auto conflict = [&] {
    std::string list;
    for (auto f : faces) list += (list.empty() ? "" : ", ") + face_label(scene, f);
    return Error(where(md, I) + " lies on " + list +
                 " that prescribe different motions along one direction; separate the faces");
  };
  for (Candidate c : in) {
    for (const Candidate& e : out) {
      const double proj = c.e.dot(e.e);
      c.e -= proj * e.e;
      if (e.value_face >= 0 && proj != 0) {
        if (c.value_face >= 0 && c.value_face != e.value_face && c.coef != 0) throw conflict();
        if (c.value_face < 0) c.value_face = e.value_face, c.coef = 0;
        c.coef -= proj * e.coef;
      }
    }
    const double len = c.e.norm();
    // a remainder under 1e-8 of a unit direction is round-off (as is a value coefficient under 1e-8)
    if (len < 1e-8) {  // already held: it must ask for what the others ask
      if (c.value_face >= 0 && std::abs(c.coef) > 1e-8) throw conflict();
      continue;
    }
    c.e /= len, c.coef /= len;
    out.push_back(c);
  }
  return out;
}

}  // namespace

std::string face_label(const Scene& scene, std::size_t f) {
  const std::size_t fixed = scene.fixed_faces.size(), reported = reported_faces(scene);
  if (f < fixed) return "boundaries.fixed_faces '" + scene.fixed_faces[f].name + "'";
  if (f < reported) return "boundaries.prescribed_faces '" + scene.prescribed_faces[f - fixed].name + "'";
  return "boundaries.symmetry_planes entry " + std::to_string(f - reported);
}

void build_constraints(Model& md, const Subdomain& sub, const Scene& scene) {
  md.constraint_offsets.assign(1, 0);
  md.constraint_dirs.clear(), md.constraint_coef.clear(), md.constraint_value_face.clear(), md.constraint_face.clear();
  md.ebc_particles.clear(), md.ebc_cols.clear(), md.ebc_N.clear();
  md.ebc_offsets.assign(1, 0);
  md.face_particles.assign(all_faces(scene), 0);

  const LocalShapes shapes(md.Xr, sub.volume, md.spacing, md.body, scene);
  std::vector<std::size_t> faces;
  for (std::size_t I = 0; I < md.n; ++I) {
    const std::vector<Candidate> dirs = orthonormalize(md, I, candidates(md, I, scene, faces), scene, faces);
    for (const auto& c : dirs) {
      md.constraint_dirs.insert(md.constraint_dirs.end(), c.e.data(), c.e.data() + 3);
      md.constraint_coef.push_back(c.coef);
      md.constraint_value_face.push_back(c.value_face);
      md.constraint_face.push_back(c.face);
    }
    md.constraint_offsets.push_back(std::int32_t(md.constraint_coef.size()));
    if (dirs.empty() || !md.owned[I]) continue;
    if (!md.surface[I])
      throw Error(where(md, I) + " lies on " + face_label(scene, faces.front()) +
                  " but inside the part: a fixed face, prescribed face or symmetry plane must be a face of the part");
    for (auto f : faces) ++md.face_particles[f];
    // the row N_J(X_I): rkprep made the whole support of an owned surface particle local. The nodal
    // method needs it only to measure its error (and to show u^h), so it does without where the
    // moment matrix is singular (a quadratic basis at a corner); the exact one cannot.
    const std::size_t k0 = md.ebc_cols.size();
    if (!shapes.append(&md.Xr[3 * I], md.body[I], md.ebc_cols, md.ebc_N).regular) {
      if (scene.discretization.ebc_method == "transformation")
        throw Error("the RK moment matrix is singular at the constrained " + where(md, I) +
                    "; increase discretization.dilation or use discretization.ebc_method: nodal");
      md.ebc_cols.resize(k0), md.ebc_N.resize(k0);
      continue;
    }
    md.ebc_particles.push_back(std::int32_t(I));
    md.ebc_offsets.push_back(std::int32_t(md.ebc_cols.size()));
  }
  // the offsets grow with I: the last fits in 32 bits only if every one does
  checked_int(std::int64_t(md.constraint_coef.size()), "rank " + std::to_string(md.rank) + ": the constraint directions");
  checked_int(std::int64_t(md.ebc_cols.size()), "rank " + std::to_string(md.rank) + ": the constrained particles' rows (entries)");
}

}  // namespace rk
