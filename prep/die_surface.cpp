#include "die_surface.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <sstream>
#include <unordered_map>

#include "die_search.hpp"
#include "cad_format.hpp"
#include "error.hpp"
#include "gmsh_session.hpp"

namespace rk {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

struct Soup {
  std::vector<Kernel::Point_3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

Soup gmsh_boundary(const Die& die, double spacing) {
  const std::string ext = lower_extension(die.cad);
  const double h = spacing / die.unit;
  GmshSession session(h);
  if (ext == ".geo") {
    gmsh::open(die.cad);
  } else if (declares_its_unit(ext) || ext == ".brep") {
    gmsh::merge(die.cad);
    gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  } else {
    throw Error("die '" + die.name + "': " + die.cad + ": unsupported CAD format '" + ext +
                "' (a die takes .geo, .step/.stp, .iges/.igs or .brep; an STL die is not read)");
  }
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 64);  // chord sagitta 0.12 % of the radius ...
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.25 * h);  // ... or a quarter spacing: finer than the particles can feel
  gmsh::vectorpair volumes, surfaces;
  gmsh::model::getEntities(volumes, 3);
  if (volumes.empty())
    throw Error("die '" + die.name + "': " + die.cad + ": the CAD holds no closed solid; a die must be a solid " +
                "whose surface faces the workpiece" + (GmshSession::errors().empty() ? "" : ": " + GmshSession::errors()));
  gmsh::model::getBoundary(volumes, surfaces, true, false, false);
  gmsh::model::mesh::generate(2);

  Soup soup;
  std::unordered_map<std::size_t, std::size_t> index;
  auto vertex = [&](std::size_t tag) {  // coordinates are filled in below
    auto [it, fresh] = index.emplace(tag, soup.points.size());
    if (fresh) soup.points.emplace_back(0, 0, 0);
    return it->second;
  };
  for (auto [dim, tag] : surfaces) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, nodes;
    gmsh::model::mesh::getElements(types, etags, nodes, 2, std::abs(tag));
    for (std::size_t t = 0; t < types.size(); ++t) {
      const int per = types[t] == 2 ? 3 : types[t] == 3 ? 4 : 0;
      if (per == 0) throw Error("die '" + die.name + "': unsupported surface element type " + std::to_string(types[t]));
      for (std::size_t e = 0; e < etags[t].size(); ++e) {
        std::size_t v[4];
        for (int a = 0; a < per; ++a) v[a] = vertex(nodes[t][e * per + a]);
        soup.triangles.push_back({v[0], v[1], v[2]});
        if (per == 4) soup.triangles.push_back({v[0], v[2], v[3]});
      }
    }
  }
  std::vector<std::size_t> all;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(all, coord, param, -1, -1, true, false);
  for (std::size_t k = 0; k < all.size(); ++k) {
    auto it = index.find(all[k]);
    if (it != index.end())
      soup.points[it->second] = Kernel::Point_3(coord[3 * k] * die.unit, coord[3 * k + 1] * die.unit, coord[3 * k + 2] * die.unit);
  }
  if (soup.triangles.empty()) throw Error("die '" + die.name + "': " + die.cad + ": meshing gave no surface triangles");
  // A die smaller than a particle spacing across is almost always drawn in another unit (one in metres read
  // as mm: 40 um, buried inside the billet, where no particle is deep enough to refuse it): refused by name
  double extent = 0;
  for (int d = 0; d < 3; ++d) {
    const auto [a, b] = std::minmax_element(soup.points.begin(), soup.points.end(),
                                            [d](const Kernel::Point_3& p, const Kernel::Point_3& q) { return p[d] < q[d]; });
    extent = std::max(extent, CGAL::to_double((*b)[d] - (*a)[d]));
  }
  if (extent < spacing) {
    std::ostringstream s;
    s << "die '" << die.name << "': " << die.cad << " is " << extent << " m across with its unit of " << die.unit
      << " m, less than one particle spacing (" << spacing << " m), so no particle can feel it: check its unit";
    throw Error(s.str());
  }
  return soup;
}

}  // namespace

DieSurface mesh_die(const Die& die, double spacing) {
  try {
    require_file(die.cad, "CAD file");
  } catch (const Error& e) {
    throw Error("die '" + die.name + "': " + e.what());
  }
  Soup soup;
  try {
    soup = gmsh_boundary(die, spacing);
  } catch (const std::string& e) {  // gmsh 4.8 throws std::string
    throw Error("die '" + die.name + "': " + die.cad + ": gmsh failed: " + e);
  }
  PMP::orient_polygon_soup(soup.points, soup.triangles);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.triangles, mesh);
  if (!CGAL::is_closed(mesh))
    throw Error("die '" + die.name + "': " + die.cad + ": the die surface is not closed (a die must be a solid)");
  PMP::orient_to_bound_a_volume(mesh);  // outward normals
  DieSurface out;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out.vertices.insert(out.vertices.end(), {p.x(), p.y(), p.z()});
  }
  for (auto f : mesh.faces())
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) out.triangles.push_back(std::int32_t(v.idx()));
  return out;
}

void check_workpiece_outside(const DieSurface& surface, const Die& die, const VolumeMesh& workpiece, double spacing) {
  const DieSearch search(surface, spacing);
  for (std::size_t i = 0; i < workpiece.node_count(); ++i) {
    const DieHit hit = search.nearest(&workpiece.X[3 * i]);
    if (hit.found && hit.gap < -0.05 * spacing) {  // touching within the die facets' chord error is fine
      std::ostringstream s;
      s << "die '" << die.name << "' (" << die.cad << "): the workpiece starts inside the die: particle " << i
        << " at (" << workpiece.X[3 * i] << ", " << workpiece.X[3 * i + 1] << ", " << workpiece.X[3 * i + 2]
        << ") m is " << -hit.gap << " m deep";
      throw Error(s.str());
    }
  }
}

void check_die_off_symmetry_planes(const DieSurface& surface, const Die& die, const std::vector<SymmetryPlane>& planes,
                                   const VolumeMesh& workpiece, double spacing) {
  if (planes.empty()) return;
  const DieSearch search(surface, spacing);
  const double near = 0.05 * spacing;  // (the die facets' chord error, as check_workpiece_outside)
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const SymmetryPlane& pl = planes[k];
    std::size_t resting = 0;
    for (std::size_t i = 0; i < workpiece.node_count(); ++i) {
      const double* x = &workpiece.X[3 * i];
      const double height = (x[0] - pl.point[0]) * pl.normal[0] + (x[1] - pl.point[1]) * pl.normal[1] +
                            (x[2] - pl.point[2]) * pl.normal[2];
      if (std::abs(height) > near) continue;  // a particle in the plane,
      const DieHit hit = search.nearest(x);
      if (!hit.found || std::abs(hit.gap) > near) continue;  // on the die,
      const double along = std::abs(hit.normal[0] * pl.normal[0] + hit.normal[1] * pl.normal[1] + hit.normal[2] * pl.normal[2]);
      if (along > 0.99) ++resting;  // on a face that lies in the plane (not on an edge of a cut)
    }
    if (resting > 0) {
      std::ostringstream s;
      s << "die '" << die.name << "' (" << die.cad << "): " << resting << " particles rest on a face of it that lies in "
        << "symmetry plane " << k << " (point (" << pl.point[0] << ", " << pl.point[1] << ", " << pl.point[2]
        << "), normal (" << pl.normal[0] << ", " << pl.normal[1] << ", " << pl.normal[2] << ")): the plane holds the "
        << "part there already, so the die would carry none of the load; remove the plane (the die holds the part) "
           "or the die";
      throw Error(s.str());
    }
  }
}

}  // namespace rk
