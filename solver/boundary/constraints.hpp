// Essential boundary conditions as constraints on the displacement field (seed Sec. 2, eq. (4)):
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

}  // namespace rk
