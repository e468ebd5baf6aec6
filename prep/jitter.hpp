// Irregular particle layouts for the stability study: every interior particle moves by a
// pseudo-random offset of up to `fraction` x its spacing along each axis. Surface particles stay on
// the surface; the integration cells and points stay where the mesh put them, so only the particle
// layout (the shape functions) becomes irregular. Deterministic: the same scene gives the same
// layout on every machine and rank count.
#pragma once
#include <vector>

#include "cad_mesh.hpp"

namespace rk {

// Moves the interior nodes of mesh in place; fraction 0 leaves it unchanged.
void jitter_interior(VolumeMesh& mesh, const std::vector<double>& spacing, double fraction);

}  // namespace rk
