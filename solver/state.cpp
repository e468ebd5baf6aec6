#include "state.hpp"

namespace rk {

State State::initial(const Model& md, const double velocity[3], const double gradient[9]) {
  State st;
  st.u.assign(3 * md.n, 0.0);
  st.v.resize(3 * md.n);
  for (std::size_t I = 0; I < md.n; ++I)
    for (int i = 0; i < 3; ++i)
      st.v[3 * I + i] = velocity[i] + gradient[3 * i] * md.X[3 * I] + gradient[3 * i + 1] * md.X[3 * I + 1] +
                        gradient[3 * i + 2] * md.X[3 * I + 2];
  st.force.assign(3 * md.n, 0.0);
  st.partial.assign(kForceStride * md.n, Fixed(0));
  st.F.assign(9 * md.m, 0.0);
  st.J.assign(md.m, 1.0);
  st.P.assign(9 * md.m, 0.0);
  st.tau.assign(6 * md.m, 0.0);
  st.cp_inv.assign(6 * md.m, 0.0);
  for (std::size_t g = 0; g < md.m; ++g) st.cp_inv[6 * g] = st.cp_inv[6 * g + 1] = st.cp_inv[6 * g + 2] = 1.0;
  st.ep.assign(md.m, 0.0);
  st.psi.assign(md.m, 0.0);
  st.wp.assign(md.m, 0.0);
  st.force_bound.assign(md.m, 0.0);
  st.cell_J.assign(md.cells, 1.0);
  return st;
}

}  // namespace rk
