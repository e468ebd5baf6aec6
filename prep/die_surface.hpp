// Rigid dies from CAD: the die solid's boundary is meshed into triangles by gmsh, checked closed and
// oriented with outward normals (toward the workpiece) by CGAL, and a workpiece particle that starts
// inside a die is an error naming the die.
#pragma once
#include "cad_mesh.hpp"
#include "scene.hpp"
#include "subdomain.hpp"

namespace rk {

DieSurface mesh_die(const Die& die, double spacing);

void check_workpiece_outside(const DieSurface& surface, const Die& die, const VolumeMesh& workpiece, double spacing);

// A die face in a symmetry plane with the part resting on it: the plane holds the part's face there
// already, so the die would carry none of the load (its force read low, the run otherwise fine). A die
// cut by the plane (a quarter model's) meets the part only along the cut's edges: it passes.
void check_die_off_symmetry_planes(const DieSurface& surface, const Die& die, const std::vector<SymmetryPlane>& planes,
                                   const VolumeMesh& workpiece, double spacing);

}  // namespace rk
