#include "boundary/symmetry.hpp"

namespace rk {

void apply_symmetry(const Model& md, State& st) {
  for (std::size_t I = 0; I < md.n; ++I)
    for (auto k = md.constraint_offsets[I]; k < md.constraint_offsets[I + 1]; ++k) {
      const double* e = &md.constraint_dirs[3 * std::size_t(k)];
      double* v = &st.v[3 * I];
      const double vn = v[0] * e[0] + v[1] * e[1] + v[2] * e[2];
      for (int i = 0; i < 3; ++i) v[i] -= vn * e[i];
    }
}

}  // namespace rk
