// For the contact tests: the scene's part on one rank, and how many particles have their material,
// X_I + u^h(X_I) with u^h evaluated from the RK shape functions directly (not from the model's
// stored rows), above the plane z = top, and how many have their coefficient X_I + d_I there.
#pragma once
#include <cstdint>
#include <vector>

#include "cad_mesh.hpp"
#include "discretize.hpp"
#include "rk/local_shapes.hpp"
#include "model.hpp"
#include "partition.hpp"
#include "scene.hpp"
#include "state.hpp"

// The scene's part meshed, discretized and built on one rank, as rkprep and rksolve would.
inline rk::Model one_rank_model(const rk::Scene& scene, const std::vector<rk::DieSurface>& dies) {
  const rk::VolumeMesh mesh = rk::mesh_cad({scene.geometry.cad, scene.geometry.unit, scene.discretization.spacing});
  const rk::Discretization disc = rk::discretize(mesh, scene.discretization.gauss_order, scene.discretization.cell_rule);
  const auto cell_rank = rk::partition_cells(mesh, disc, 1, "metis-kway");
  return rk::build_model(
      rk::build_subdomains({mesh, disc, cell_rank, 1, scene.discretization.dilation, scene.prep_hash, dies})[0], scene);
}

struct AboveCount {
  std::int64_t material = 0, coefficients = 0;
  bool regular = true;  // every particle's moment matrix was regular
};

inline AboveCount count_above(const rk::Model& md, const rk::Scene& scene, const rk::State& st, double top) {
  const rk::LocalShapes shapes(md.X, md.volume, md.spacing, md.body, scene);
  AboveCount c;
  std::vector<std::int32_t> cols;
  std::vector<double> N;
  for (std::size_t I = 0; I < md.n; ++I) {
    cols.clear(), N.clear();
    c.regular &= shapes.append(&md.X[3 * I], 0, cols, N).regular;
    double uz = 0;
    for (std::size_t k = 0; k < cols.size(); ++k) uz += N[k] * st.u[3 * std::size_t(cols[k]) + 2];
    c.material += md.X[3 * I + 2] + uz > top;
    c.coefficients += md.X[3 * I + 2] + st.u[3 * I + 2] > top;
  }
  return c;
}

// A rigid lift of every coefficient by `lift` along z through the plane z = top: the particles and
// points it carries past the plane, and the sum of their penalty forces s m / dt^2 times their depth
// (m: a particle's mass, or rho w_g at a point). A translation moves the material like the particles.
struct LiftedPast {
  std::int64_t particles = 0, points = 0;
  double force = 0;
};

inline LiftedPast lifted_past(const rk::Model& md, double lift, double top, double s, double dt) {
  LiftedPast r;
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.X[3 * I + 2] + lift > top) ++r.particles, r.force += s * md.mass[I] / (dt * dt) * (md.X[3 * I + 2] + lift - top);
  for (std::size_t g = 0; g < md.m; ++g)
    if (md.point_X[3 * g + 2] + lift > top)
      ++r.points, r.force += s * md.material_at(g).density * md.weight[g] / (dt * dt) * (md.point_X[3 * g + 2] + lift - top);
  return r;
}
