// STL workpieces: CGAL checks that the triangle soup bounds a volume (closed, manifold, consistently
// oriented, non-zero volume) before gmsh meshes it; each failure is one message naming the file.
#pragma once
#include <string>

namespace rk {

void check_stl_solid(const std::string& path);

}  // namespace rk
