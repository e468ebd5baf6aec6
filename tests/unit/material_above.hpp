// For the contact tests: how many particles have their material, X_I + u^h(X_I) with u^h evaluated
// from the RK shape functions directly (not from the model's stored rows), above the plane z = top,
// and how many have their coefficient X_I + d_I there.
#pragma once
#include <cstdint>
#include <vector>

#include "local_shapes.hpp"
#include "model.hpp"
#include "scene.hpp"
#include "state.hpp"

struct AboveCount {
  std::int64_t material = 0, coefficients = 0;
  bool regular = true;  // every particle's moment matrix was regular
};

inline AboveCount count_above(const rk::Model& md, const rk::Scene& scene, const rk::State& st, double top) {
  const rk::LocalShapes shapes(md.X, md.volume, md.spacing, scene);
  AboveCount c;
  std::vector<std::int32_t> cols;
  std::vector<double> N, dN;
  for (std::size_t I = 0; I < md.n; ++I) {
    cols.clear(), N.clear(), dN.clear();
    c.regular &= shapes.append(&md.X[3 * I], cols, N, dN).regular;
    double uz = 0;
    for (std::size_t k = 0; k < cols.size(); ++k) uz += N[k] * st.u[3 * std::size_t(cols[k]) + 2];
    c.material += md.X[3 * I + 2] + uz > top;
    c.coefficients += md.X[3 * I + 2] + st.u[3 * I + 2] > top;
  }
  return c;
}
