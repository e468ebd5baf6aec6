#include "stl_check.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
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
  // A facet repeated (the same three corners) is dropped by CGAL's repair below, but gmsh meshes the file as it
  // is and failed ("Wrong topology of boundary mesh for parametrization"): refused here, by count
  {
    std::vector<std::array<double, 9>> corners;
    corners.reserve(triangles.size());
    for (const auto& t : triangles) {
      std::array<std::array<double, 3>, 3> c;
      for (int a = 0; a < 3; ++a) c[std::size_t(a)] = {points[t[std::size_t(a)]].x(), points[t[std::size_t(a)]].y(), points[t[std::size_t(a)]].z()};
      std::sort(c.begin(), c.end());
      corners.push_back({c[0][0], c[0][1], c[0][2], c[1][0], c[1][1], c[1][2], c[2][0], c[2][1], c[2][2]});
    }
    std::sort(corners.begin(), corners.end());
    const auto repeated = std::size_t(corners.end() - std::unique(corners.begin(), corners.end()));
    if (repeated > 0)
      throw Error(path + ": " + std::to_string(repeated) + " of its " + std::to_string(triangles.size()) +
                  " facets repeat another facet, which gmsh cannot mesh; export the STL again, or remove the duplicates");
  }
  PMP::repair_polygon_soup(points, triangles);  // merges the duplicated vertices of STL facets
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
