// CAD -> volume mesh with gmsh (OpenCASCADE for STEP/IGES/BREP, .geo scripts as written).
// Particles are the mesh nodes (so they lie on the CAD surfaces); integration cells are its elements.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rk {

enum class CellType : std::int8_t { tet4 = 4, hex8 = 8 };

struct VolumeMesh {
  std::vector<double> X;               // 3 per node, metres
  std::vector<std::uint8_t> surface;   // 1 if the node lies on the solid's boundary
  std::vector<std::uint8_t> body;      // the body each node belongs to (Scene::bodies; 0 the part)
  std::vector<std::int32_t> cell_offsets{0};
  std::vector<std::int32_t> cell_nodes;  // gmsh node order within each cell
  std::size_t node_count() const { return surface.size(); }
  std::size_t cell_count() const { return cell_offsets.size() - 1; }
};

struct MeshRequest {
  std::string cad;       // path
  double unit = 1.0;     // metres per CAD unit
  double spacing = 0;    // target particle spacing, metres
  double dilation = 0;   // the supports' radius over the particles' spacing: solids of the file closer than
                         // that reach are refused (0: not checked)
};

// Meshes the solid. .geo scripts see the spacing (in CAD units) as the number `h`
// (as with `gmsh -setnumber h ...`); other CAD is meshed with all-hex subdivision at that spacing.
VolumeMesh mesh_cad(const MeshRequest& request);

// Appends `other` (a body's own mesh) to `mesh`, its nodes of body `body`.
void append_body(VolumeMesh& mesh, const VolumeMesh& other, int body);

// Refuses bodies that start closer than the part's contact acts (0.75 of the spacing,
// solver/contact/part_contact.hpp), naming the two and where: they would be thrown apart at the first step.
void check_bodies_apart(const VolumeMesh& mesh, const std::vector<std::string>& names, double spacing);

// The faces of a cell (gmsh node order: 8 a hexahedron, 4 a tetrahedron), nodes in cyclic order.
const std::vector<std::vector<int>>& cell_faces(int nodes_per_cell);

// Per cell, per face of cell_faces: 1 where no other cell has the face's node set (the boundary).
std::vector<std::vector<std::uint8_t>> boundary_face_flags(const VolumeMesh& mesh);

// The faces of the cells that no other cell shares: the solid's boundary, each as its nodes in
// counter-clockwise order seen from outside (CSR: face_offsets[f] .. face_offsets[f + 1] in
// face_nodes), with the cell it bounds.
struct BoundaryFaces {
  std::vector<std::int32_t> face_offsets{0}, face_nodes, cell;
  std::size_t size() const { return cell.size(); }
};
BoundaryFaces boundary_faces(const VolumeMesh& mesh);

// The spacing the mesh achieved: the median length of its cells' edges (metres), to set beside the
// asked discretization.spacing (a CAD's own features can force a finer mesh).
double median_edge(const VolumeMesh& mesh);

}  // namespace rk
