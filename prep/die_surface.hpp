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

}  // namespace rk
