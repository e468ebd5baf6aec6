// Reference-configuration updates. Total-Lagrangian RK kernels keep the neighbours and the support
// shapes of t = 0; where the material shears hard (back extrusion: the metal turning the punch
// corner) the supports become thin slivers that no longer hold the material together. An update
// makes the current configuration the new reference: particles and integration points move to where
// the material they sit in is, x = X + u^h(X) (the points keep their t = 0 volumes as weights, with
// J_ref; material pressed into a die or a wall, where the contact holds the field, stays at its
// spring's depth), the particles take the material's velocity v^h(X_I) (the kinetic energy this
// smooths away is booked as update_work), the shape functions are rebuilt there on supports of the
// t = 0 size, grown once where the particles surround a point poorly, and the plastic state is pushed
// forward (C_p^-1 <- Fbar C_p^-1 Fbar^T, so the next stress update is unchanged). Masses and stored
// energies are untouched. Why each choice: docs/decisions.md, "Reference updates".
//
// Parallel: the points stay on their rank; the rank's local particles are found again with rkprep's
// rules on the new reference (local_particles.hpp) among a halo, the owned particles within reach of
// its points (sent by their owners; no rank holds the whole part), and the overlap maps come from the
// owners, who learn every holder of their particles. Every rank count builds the same shape
// functions (bitwise).
#pragma once
#include <functional>

#include "model.hpp"
#include "parallel/comm.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

// Puts owned particle I's new reference position x (3) onto its essential-BC faces.
using Projection = std::function<void(std::size_t I, double* x)>;

// The update at the current state (collective).
void update_reference(Model& md, State& st, const Scene& scene, const Comm& comm, const Projection& project);

// Rebuilds this rank's model on the reference positions X + d^ref and moves the particle state onto
// the new local particles. Reads only the owned particles' X, d, v, d^ref and md.point_X, so it also
// restores a checkpoint written after updates (collective; throws rk::Error, e.g. for a singular
// moment matrix, naming the point).
void rebuild_on_reference(Model& md, State& st, const Scene& scene, const Comm& comm);

}  // namespace rk
