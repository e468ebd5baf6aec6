#include "stl_check.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <vector>

#include "error.hpp"

namespace rk {

void check_stl_solid(const std::string& path) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::vector<Kernel::Point_3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  if (!CGAL::IO::read_polygon_soup(path, points, triangles) || triangles.empty())
    throw Error(path + ": cannot read the STL file (or it holds no triangles)");
  const std::size_t facets = triangles.size();
  PMP::repair_polygon_soup(points, triangles);  // merges the duplicated vertices of STL facets
  // and drops repeated facets and facets whose corners coincide, which gmsh meshes from the file as they are
  // ("Wrong topology of boundary mesh for parametrization"): said here, by count
  if (triangles.size() != facets)
    throw Error(path + ": " + std::to_string(facets - triangles.size()) + " of its " + std::to_string(facets) +
                " facets repeat another facet or have coinciding corners (zero area), which gmsh cannot mesh; "
                "export the STL again, or repair it (remove duplicate and degenerate facets)");
  if (!PMP::is_polygon_soup_a_polygon_mesh(triangles))
    throw Error(path + ": the STL surface is not a consistently oriented manifold (flipped or non-manifold facets)");
  CGAL::Surface_mesh<Kernel::Point_3> mesh;
  PMP::polygon_soup_to_polygon_mesh(points, triangles, mesh);
  std::size_t border = 0;
  for (auto h : mesh.halfedges()) border += mesh.is_border(h);
  if (border > 0)
    throw Error(path + ": the STL surface is not watertight (" + std::to_string(border) + " open edges)");
  const double volume = PMP::volume(mesh);
  if (!(std::abs(volume) > 0)) throw Error(path + ": the STL solid has zero volume");
  if (volume < 0) throw Error(path + ": the STL facets point inward (negative volume); flip their orientation");
}

}  // namespace rk
