// Essential boundary conditions as constraints on the displacement field (Wang et al. 2007, Sec. 2, eq. (4)):
// at a particle X_I on a face, e_k . u^h(X_I) = g_k(t) for each constrained direction e_k, with
// u^h(X_I) = sum_J N_J(X_I) d_J. Built once from the scene's faces (fixed faces, prescribed faces,
// symmetry planes): the directions of each particle are orthonormalized (Gram-Schmidt, so planes of
// any normal combine exactly) and each owned constrained particle gets its row N_J(X_I).
#pragma once
#include "scene.hpp"
#include "subdomain.hpp"

namespace rk {

struct Model;

// Fills md.constraint_* and md.ebc_*. Throws rk::Error naming the face and particle for a face
// that holds no particle (checked by the caller over all ranks), a plane through the inside of
// the part, or two faces that prescribe different motions of one direction.
void build_constraints(Model& md, const Subdomain& sub, const Scene& scene);

// Faces in reporting order: the fixed faces, then the prescribed ones.
inline std::size_t reported_faces(const Scene& scene) { return scene.fixed_faces.size() + scene.prescribed_faces.size(); }

// Every face in one numbering (md.face_particles): the reported faces, then the symmetry planes.
inline std::size_t all_faces(const Scene& scene) { return reported_faces(scene) + scene.symmetry_planes.size(); }

// The scene key of face f of that numbering, for messages: "boundaries.fixed_faces 'clamp'".
std::string face_label(const Scene& scene, std::size_t f);

}  // namespace rk
