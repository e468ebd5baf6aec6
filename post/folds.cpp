#include "folds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <unordered_map>

namespace rk {

namespace {

// The faces of a VTK hexahedron and tetrahedron, by corner.
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
constexpr int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

double distance2(const double* a, const double* b) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

}  // namespace

FoldFinder::FoldFinder(const VtuCells& cells, const std::vector<double>& X0, double spacing,
                       const std::vector<SymmetryPlane>& planes)
    : X0_(X0), h_(spacing) {
  // every cell's faces by their sorted corners: a face that no other cell shares is on the surface
  struct CellFace {
    std::array<std::int64_t, 4> key;   // the corners sorted (-1 first for a triangle)
    std::array<std::int64_t, 5> face;  // the corners in order, then a corner of its cell off the face
  };
  std::vector<CellFace> all;
  for (std::size_t c = 0; c < cells.types.size(); ++c) {
    const std::int64_t* n = &cells.connectivity[std::size_t(c == 0 ? 0 : cells.offsets[c - 1])];
    const bool hex = cells.types[c] == kVtkHexahedron;
    const int count = hex ? 6 : 4, corners = hex ? 4 : 3;
    for (int f = 0; f < count; ++f) {
      std::array<std::int64_t, 5> face{-1, -1, -1, -1, -1};
      for (int k = 0; k < corners; ++k) face[k] = n[hex ? kHexFaces[f][k] : kTetFaces[f][k]];
      for (int k = 0; k < (hex ? 8 : 4) && face[4] < 0; ++k)  // a corner of the cell off this face
        if (std::find(face.begin(), face.begin() + corners, n[k]) == face.begin() + corners) face[4] = n[k];
      std::array<std::int64_t, 4> key{face[0], face[1], face[2], face[3]};
      std::sort(key.begin(), key.end());
      all.push_back({key, face});
    }
  }
  std::sort(all.begin(), all.end(), [](const CellFace& a, const CellFace& b) { return a.key < b.key; });
  std::vector<char> surface(X0.size() / 3, 0);
  for (std::size_t k = 0; k < all.size(); ++k) {
    if ((k > 0 && all[k - 1].key == all[k].key) || (k + 1 < all.size() && all[k + 1].key == all[k].key)) continue;
    const std::array<std::int64_t, 5>& face = all[k].face;
    bool mirrored = false;  // on a symmetry plane: the mirror's material lies across, not a free surface
    for (const SymmetryPlane& p : planes) {
      bool on = true;
      for (int k = 0; k < 4 && face[k] >= 0; ++k) {
        const double* X = &X0[3 * std::size_t(face[k])];
        on = on && std::abs((X[0] - p.point[0]) * p.normal[0] + (X[1] - p.point[1]) * p.normal[1] +
                            (X[2] - p.point[2]) * p.normal[2]) < 1e-6 * spacing;
      }
      mirrored = mirrored || on;
    }
    if (mirrored) continue;
    faces_.push_back(face);
    for (int k = 0; k < 4 && face[k] >= 0; ++k) surface[std::size_t(face[k])] = 1;
  }
  for (std::size_t I = 0; I < surface.size(); ++I)
    if (surface[I]) nodes_.push_back(std::int64_t(I));
}

std::vector<std::int64_t> FoldFinder::find(const std::vector<double>& x, double time, std::vector<Fold>& found) {
  const std::size_t n = x.size() / 3;
  fold_of_.resize(n, -1);
  std::vector<std::int64_t> flag(n, 0);
  // outward normals at the surface particles: their faces' area normals, each turned away from its cell
  std::vector<double> normal(3 * n, 0.0);
  for (const auto& face : faces_) {
    const int corners = face[3] < 0 ? 3 : 4;
    const double *a = &x[3 * std::size_t(face[0])], *b = &x[3 * std::size_t(face[1])], *c = &x[3 * std::size_t(face[2])];
    // the diagonals' cross product (c - a) x (d - b): twice the area normal of a quad, and of a
    // triangle with d = a
    const double* d = corners == 4 ? &x[3 * std::size_t(face[3])] : a;
    double e1[3], e2[3], m[3], centre[3];
    for (int i = 0; i < 3; ++i)
      e1[i] = c[i] - a[i], e2[i] = d[i] - b[i], centre[i] = (a[i] + b[i] + c[i] + (corners == 4 ? d[i] : 0)) / corners;
    m[0] = e1[1] * e2[2] - e1[2] * e2[1], m[1] = e1[2] * e2[0] - e1[0] * e2[2], m[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double* off = &x[3 * std::size_t(face[4])];
    const double side = (off[0] - centre[0]) * m[0] + (off[1] - centre[1]) * m[1] + (off[2] - centre[2]) * m[2];
    const double sign = side > 0 ? -1.0 : 1.0;
    for (int k = 0; k < corners; ++k)
      for (int i = 0; i < 3; ++i) normal[3 * std::size_t(face[k]) + i] += sign * m[i];
  }
  // pairs within kReach spacings: a grid of bins that size over the surface particles
  const double bin = kReach * h_, reach2 = bin * bin, apart2 = kApart * kApart * h_ * h_, same2 = kSame * kSame * h_ * h_;
  auto key = [&](const double* p, int di, int dj, int dk) {
    const auto q = [&](int i, int d) { return std::int64_t(std::floor(p[i] / bin)) + d; };
    return (q(0, di) * 73856093) ^ (q(1, dj) * 19349663) ^ (q(2, dk) * 83492791);
  };
  std::unordered_multimap<std::int64_t, std::int64_t> grid;
  for (std::int64_t I : nodes_) grid.emplace(key(&x[3 * std::size_t(I)], 0, 0, 0), I);
  for (std::int64_t I : nodes_) {
    const double* p = &x[3 * std::size_t(I)];
    const double* nI = &normal[3 * std::size_t(I)];
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj)
        for (int dk = -1; dk <= 1; ++dk) {
          const auto [lo, hi] = grid.equal_range(key(p, di, dj, dk));
          for (auto it = lo; it != hi; ++it) {
            const std::int64_t J = it->second;
            if (J == I || distance2(p, &x[3 * std::size_t(J)]) > reach2) continue;
            if (distance2(&X0_[3 * std::size_t(I)], &X0_[3 * std::size_t(J)]) < apart2) continue;
            const double* nJ = &normal[3 * std::size_t(J)];
            const double dot = nI[0] * nJ[0] + nI[1] * nJ[1] + nI[2] * nJ[2];
            const double len = std::sqrt((nI[0] * nI[0] + nI[1] * nI[1] + nI[2] * nI[2]) * (nJ[0] * nJ[0] + nJ[1] * nJ[1] + nJ[2] * nJ[2]));
            if (len > 0 && dot < -0.5 * len) flag[std::size_t(I)] = 1;  // facing each other
          }
        }
  }
  // the flagged particles in clusters (within two spacings): each a fold; a new one when no fold
  // found at an earlier frame lies within kSame spacings of it
  std::vector<std::int64_t> on;
  for (std::int64_t I : nodes_)
    if (flag[std::size_t(I)]) on.push_back(I);
  std::vector<std::size_t> root(on.size());
  std::iota(root.begin(), root.end(), 0);
  const auto find_root = [&](std::size_t a) {
    while (root[a] != a) a = root[a] = root[root[a]];
    return a;
  };
  for (std::size_t a = 0; a < on.size(); ++a)
    for (std::size_t b = a + 1; b < on.size(); ++b)
      if (distance2(&x[3 * std::size_t(on[a])], &x[3 * std::size_t(on[b])]) < 4 * h_ * h_) root[find_root(b)] = find_root(a);
  std::map<std::size_t, std::vector<std::int64_t>> clusters;  // by root: the members
  for (std::size_t a = 0; a < on.size(); ++a) clusters[find_root(a)].push_back(on[a]);
  std::vector<std::int64_t> earlier;  // the particles of the folds found at earlier frames
  for (std::int64_t I : nodes_)
    if (fold_of_[std::size_t(I)] >= 0) earlier.push_back(I);
  for (const auto& [r, members] : clusters) {
    int id = -1;  // a fold found before: one of its particles is in the cluster, or near it
    for (std::int64_t I : members) id = std::max(id, fold_of_[std::size_t(I)]);
    for (std::size_t k = 0; k < earlier.size() && id < 0; ++k)
      for (std::int64_t I : members)
        if (distance2(&x[3 * std::size_t(I)], &x[3 * std::size_t(earlier[k])]) < same2) id = fold_of_[std::size_t(earlier[k])];
    if (id < 0) {
      Fold f;
      f.time = time, f.particles = members.size();
      for (std::int64_t I : members)
        for (int i = 0; i < 3; ++i) f.at[std::size_t(i)] += x[3 * std::size_t(I) + i] / double(members.size());
      id = int(found.size());
      found.push_back(f);
    }
    for (std::int64_t I : members) fold_of_[std::size_t(I)] = id;
  }
  return flag;
}

std::string describe_fold(const Fold& f) {
  char text[200];
  std::snprintf(text, sizeof text, "a fold at (%.4g, %.4g, %.4g) mm from t = %.4g s (%zu surface particles)", 1e3 * f.at[0],
                1e3 * f.at[1], 1e3 * f.at[2], f.time, f.particles);
  return text;
}

}  // namespace rk
