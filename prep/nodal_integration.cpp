#include "nodal_integration.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "discretize.hpp"
#include "error.hpp"

namespace rk {
namespace {

using P3 = std::array<double, 3>;

P3 centre(const VolumeMesh& mesh, const std::int32_t* nodes, const std::vector<int>& which) {
  P3 c{0, 0, 0};
  for (int a : which)
    for (int i = 0; i < 3; ++i) c[i] += mesh.X[3 * nodes[a] + i] / double(which.size());
  return c;
}

P3 node(const VolumeMesh& mesh, std::int32_t I) { return {mesh.X[3 * I], mesh.X[3 * I + 1], mesh.X[3 * I + 2]}; }

P3 mid(const P3& a, const P3& b) { return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}; }

// Appends the 2x2 Gauss points of the bilinear quadrilateral p0 p1 p2 p3 (cyclic), its normal turned
// to point along `outward`, owned by `plus` (and `minus` across it).
void add_quad(const std::array<P3, 4>& p, const P3& outward, std::int32_t plus, std::int32_t minus, DualFaces& f) {
  static const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  auto normal = [&](double s, double t) {
    P3 xs, xt, n;
    for (int i = 0; i < 3; ++i) {
      xs[i] = (1 - t) * (p[1][i] - p[0][i]) + t * (p[2][i] - p[3][i]);
      xt[i] = (1 - s) * (p[3][i] - p[0][i]) + s * (p[2][i] - p[1][i]);
    }
    n = {xs[1] * xt[2] - xs[2] * xt[1], xs[2] * xt[0] - xs[0] * xt[2], xs[0] * xt[1] - xs[1] * xt[0]};
    return n;
  };
  const P3 nc = normal(0.5, 0.5);
  const double sign = nc[0] * outward[0] + nc[1] * outward[1] + nc[2] * outward[2] < 0 ? -1.0 : 1.0;
  // a parallelogram (flat, constant normal) integrates linear fields exactly with its centre alone
  double skew = 0, size = 0;
  for (int i = 0; i < 3; ++i)
    skew = std::max(skew, std::abs(p[0][i] + p[2][i] - p[1][i] - p[3][i])),
    size = std::max(size, std::abs(p[2][i] - p[0][i]) + std::abs(p[3][i] - p[1][i]));
  const bool parallelogram = skew <= 1e-12 * size;
  for (double t : parallelogram ? std::vector<double>{0.5} : std::vector<double>{g[0], g[1]})
    for (double s : parallelogram ? std::vector<double>{0.5} : std::vector<double>{g[0], g[1]}) {
      const P3 n = normal(s, t);
      for (int i = 0; i < 3; ++i) {
        f.X.push_back((1 - s) * (1 - t) * p[0][i] + s * (1 - t) * p[1][i] + s * t * p[2][i] + (1 - s) * t * p[3][i]);
        f.nA.push_back(sign * (parallelogram ? 1.0 : 0.25) * n[i]);
      }
      f.plus.push_back(plus);
      f.minus.push_back(minus);
    }
}

}  // namespace

DualFaces dual_faces(const VolumeMesh& mesh) {
  DualFaces f;
  const auto boundary = boundary_face_flags(mesh);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::int32_t* nodes = &mesh.cell_nodes[mesh.cell_offsets[c]];
    const int per = mesh.cell_offsets[c + 1] - mesh.cell_offsets[c];
    const auto& faces = cell_faces(per);
    std::vector<int> all(per);
    for (int a = 0; a < per; ++a) all[a] = a;
    const P3 cc = centre(mesh, nodes, all);
    // inside the cell: one quadrilateral per edge, between the edge's two nodes
    for (auto [a, b] : cell_edges(per)) {
      P3 fc[2];
      int found = 0;
      for (const auto& face : faces)
        if (std::count(face.begin(), face.end(), a) && std::count(face.begin(), face.end(), b))
          fc[found++] = centre(mesh, nodes, face);
      const P3 xa = node(mesh, nodes[a]), xb = node(mesh, nodes[b]);
      add_quad({mid(xa, xb), fc[0], cc, fc[1]}, {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]}, nodes[a], nodes[b], f);
    }
    // on the domain boundary: the part of each boundary face nearest to each of its nodes
    for (std::size_t k = 0; k < faces.size(); ++k) {
      if (!boundary[c][k]) continue;
      const auto& face = faces[k];
      const P3 fc = centre(mesh, nodes, face);
      const P3 out{fc[0] - cc[0], fc[1] - cc[1], fc[2] - cc[2]};
      const std::size_t nf = face.size();
      for (std::size_t v = 0; v < nf; ++v) {
        const P3 xv = node(mesh, nodes[face[v]]);
        const P3 next = node(mesh, nodes[face[(v + 1) % nf]]), prev = node(mesh, nodes[face[(v + nf - 1) % nf]]);
        add_quad({xv, mid(xv, next), fc, mid(prev, xv)}, out, nodes[face[v]], -1, f);
      }
    }
  }
  return f;
}

std::vector<double> dual_volumes(const VolumeMesh& mesh, const DualFaces& f) {
  std::vector<double> V(mesh.node_count(), 0.0);
  for (std::size_t q = 0; q < f.size(); ++q)
    for (const std::int32_t L : {f.plus[q], f.minus[q]}) {
      if (L < 0) continue;
      const double sign = L == f.plus[q] ? 1.0 : -1.0;
      for (int i = 0; i < 3; ++i) V[L] += sign * (f.X[3 * q + i] - mesh.X[3 * L + i]) * f.nA[3 * q + i] / 3;
    }
  return V;
}

void use_nodal_points(const VolumeMesh& mesh, Discretization& d) {
  DualFaces f = dual_faces(mesh);
  const std::vector<double> V = dual_volumes(mesh, f);
  // a node's point belongs to the first cell that has the node (whose rank owns the node), points
  // grouped by cell
  const std::size_t n = mesh.node_count();
  std::vector<std::int32_t> first(n, -1), order(n), point(n);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    for (auto k = mesh.cell_offsets[c]; k < mesh.cell_offsets[c + 1]; ++k)
      if (first[mesh.cell_nodes[k]] < 0) first[mesh.cell_nodes[k]] = std::int32_t(c);
  for (std::size_t I = 0; I < n; ++I) order[I] = std::int32_t(I);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) { return first[a] < first[b]; });
  d.point_X.clear(), d.point_weight.clear(), d.point_cell.clear();
  for (std::size_t g = 0; g < n; ++g) {
    const std::int32_t L = order[g];
    point[L] = std::int32_t(g);
    if (!(V[L] > 0))
      throw Error("mesh node " + std::to_string(L) + " at (" + std::to_string(mesh.X[3 * L]) + ", " +
                  std::to_string(mesh.X[3 * L + 1]) + ", " + std::to_string(mesh.X[3 * L + 2]) +
                  ") m has a dual cell of non-positive volume (inverted cells around it)");
    d.point_X.insert(d.point_X.end(), &mesh.X[3 * L], &mesh.X[3 * L] + 3);
    d.point_weight.push_back(V[L]);
    d.point_cell.push_back(first[L]);
  }
  for (auto& L : f.plus) L = point[L];
  for (auto& L : f.minus) L = L < 0 ? -1 : point[L];
  d.faces = std::move(f);
  d.volume = V;  // lumped masses from the same cells the points integrate over
}

}  // namespace rk
