#include "kinematics.hpp"

namespace rk {

void compute_deformation_gradient(const Model& md, State& st) {
  for (std::size_t g = 0; g < md.m; ++g) {
    double F[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (auto k = md.nbr_offsets[g]; k < md.nbr_offsets[g + 1]; ++k) {
      const double* u = &st.u[3 * std::size_t(md.nbr[k])];
      const double* d = &md.dN[3 * std::size_t(k)];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) F[3 * i + j] += u[i] * d[j];
    }
    double* out = &st.F[9 * g];
    for (int i = 0; i < 9; ++i) out[i] = F[i];
    st.J[g] = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]);
  }
  for (std::size_t c = 0; c < md.cells; ++c) {
    double wJ = 0, w = 0;
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) wJ += md.weight[g] * st.J[g], w += md.weight[g];
    st.cell_J[c] = wJ / w;
  }
}

}  // namespace rk
