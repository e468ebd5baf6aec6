#include "model.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <sstream>

#include "boundary/constraints.hpp"
#include "error.hpp"
#include "local_shapes.hpp"

namespace rk {
namespace {

void build_shape_functions(Model& md, const Subdomain& sub, const Scene& scene) {
  const LocalShapes shapes(md.Xr, sub.volume, md.spacing, scene);
  md.nbr_offsets.assign(1, 0);
  md.dN_max.resize(md.m);
  for (std::size_t g = 0; g < md.m; ++g) {
    const std::size_t k0 = md.nbr.size();
    const RkResult r = shapes.append(&md.point_X[3 * g], md.nbr, md.N, md.dN);  // ascending global id
    if (!r.regular) {
      std::ostringstream s;
      s << "rank " << md.rank << ": the RK moment matrix is singular at the integration point at (" << sub.point_X[3 * g]
        << ", " << sub.point_X[3 * g + 1] << ", " << sub.point_X[3 * g + 2] << ") m with " << md.nbr.size() - k0
        << " particles in its support (rcond " << r.rcond << "); increase discretization.dilation";
      throw Error(s.str());
    }
    double mx = 0;
    for (std::size_t k = k0; k < md.nbr.size(); ++k)
      mx = std::max(mx, std::sqrt(md.dN[3 * k] * md.dN[3 * k] + md.dN[3 * k + 1] * md.dN[3 * k + 1] +
                                  md.dN[3 * k + 2] * md.dN[3 * k + 2]));
    md.dN_max[g] = mx;
    md.nbr_offsets.push_back(std::int32_t(md.nbr.size()));
  }
}

// The shortest edge of each cell at t = 0 (hexahedra: 12 edges, tetrahedra: 6), for the time step; it
// is kept through reference updates (the step then follows the points' stretch since the update).
std::vector<double> shortest_edges(const Model& md) {
  static constexpr int kHex[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                      {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  static constexpr int kTet[12][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  std::vector<double> h0(md.cells, std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < md.cells; ++c) {
    const std::int32_t* nodes = &md.cell_nodes[md.cell_node_offsets[c]];
    const bool hex = md.cell_node_offsets[c + 1] - md.cell_node_offsets[c] == 8;
    for (int e = 0; e < (hex ? 12 : 6); ++e) {
      const int a = nodes[hex ? kHex[e][0] : kTet[e][0]], b = nodes[hex ? kHex[e][1] : kTet[e][1]];
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (md.X[3 * a + i] - md.X[3 * b + i]) * (md.X[3 * a + i] - md.X[3 * b + i]);
      h0[c] = std::min(h0[c], std::sqrt(d2));
    }
  }
  return h0;
}

}  // namespace

Model build_model(const Subdomain& sub, const Scene& scene, const std::vector<double>* initial_X) {
  Model md;
  md.rank = int(sub.rank);
  md.ranks = int(sub.ranks);
  md.n = sub.particle_count();
  md.global_id = sub.global_id;
  md.X = initial_X ? *initial_X : sub.X;
  md.Xr = sub.X;
  md.volume = sub.volume;
  md.spacing = sub.spacing;
  md.spacing0 = sub.spacing;
  md.density = scene.material.density;
  md.mass.resize(md.n);
  md.owned.resize(md.n);
  md.surface.resize(md.n);
  for (std::size_t I = 0; I < md.n; ++I) {
    md.mass[I] = md.density * sub.volume[I];
    md.owned[I] = sub.owner[I] == sub.rank;
    md.surface[I] = (sub.flags[I] & kSurface) != 0;
  }
  build_constraints(md, sub, scene);

  md.m = sub.point_count();
  md.weight = sub.point_weight;
  md.point_X = sub.point_X;
  md.cells = sub.cell_count();
  md.cell_global_id = sub.cell_global_id;
  md.cell_node_offsets = sub.cell_node_offsets;
  md.cell_nodes = sub.cell_nodes;
  md.cell_points.assign(md.cells + 1, 0);
  for (std::size_t g = 0; g < md.m; ++g) {
    if (g > 0 && sub.point_cell[g] < sub.point_cell[g - 1])
      throw Error("subdomain of rank " + std::to_string(md.rank) + ": integration points are not grouped by cell");
    ++md.cell_points[sub.point_cell[g] + 1];
  }
  for (std::size_t c = 0; c < md.cells; ++c) md.cell_points[c + 1] += md.cell_points[c];
  md.cell_h0 = shortest_edges(md);
  build_shape_functions(md, sub, scene);

  md.dies = sub.dies;
  md.neighbour_ranks = sub.neighbour_ranks;
  md.overlap = sub.overlap;
  std::vector<std::uint8_t> shared(md.n, 0);
  for (const auto& list : md.overlap)
    for (auto I : list) shared[I] = 1;
  for (std::size_t g = 0; g < md.m; ++g) {
    bool touches = false;
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1] && !touches; ++k) touches = shared[md.nbr[k]];
    (touches ? md.boundary_points : md.interior_points).push_back(std::int32_t(g));
  }

  const auto& mat = scene.material;
  md.material = mat.model == MaterialModel::j2_power
                    ? J2Params::power(mat.youngs_modulus, mat.poisson_ratio, mat.strength, mat.reference_strain, mat.exponent)
                    : J2Params::from(mat.youngs_modulus, mat.poisson_ratio, mat.yield_stress, mat.hardening_modulus,
                                     mat.model == MaterialModel::j2_linear);
  md.wave_modulus = md.material.bulk + 4.0 / 3.0 * md.material.shear;
  md.fbar = scene.discretization.volumetric == "fbar";
  return md;
}

}  // namespace rk

namespace rk {

void scale_mass(Model& md, double factor) {
  md.mass_scaling *= factor;
  md.density *= factor;
  for (auto& m : md.mass) m *= factor;
}

}  // namespace rk
