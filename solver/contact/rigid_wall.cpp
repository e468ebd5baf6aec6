#include "contact/rigid_wall.hpp"

#include <cmath>

namespace rk {

void project_onto_wall(const RigidWall& wall, const double* c, double* x) {
  double now = 0, moved = 0;
  for (int i = 0; i < 3; ++i) now += (c[i] - wall.point[i]) * wall.normal[i], moved += (x[i] - wall.point[i]) * wall.normal[i];
  const double on = 1e-12 * (std::abs(wall.point[0]) + std::abs(wall.point[1]) + std::abs(wall.point[2]) + 1.0);
  if (moved < 0 || now <= on)
    for (int i = 0; i < 3; ++i) x[i] -= moved * wall.normal[i];
}

WallResult apply_rigid_wall(const Model& md, State& st, const RigidWall& wall, double dt_next, double dt_avg,
                            const std::vector<double>& v_old) {
  WallResult r;
  const double* n = wall.normal.data();
  for (std::size_t I = 0; I < md.n; ++I) {
    double* v = &st.v[3 * I];
    double gap = 0, vn = 0;
    for (int i = 0; i < 3; ++i) {
      gap += (md.X[3 * I + i] + st.u[3 * I + i] - wall.point[i]) * n[i];
      vn += v[i] * n[i];
    }
    const double next = gap + dt_next * vn;
    if (next >= 0) continue;
    const double dvn = -next / dt_next;  // lands exactly on the plane
    for (int i = 0; i < 3; ++i) v[i] += dvn * n[i];
    if (!md.owned[I]) continue;
    ++r.contacts;
    double vbar_n = 0;
    for (int i = 0; i < 3; ++i) vbar_n += 0.5 * (v_old[3 * I + i] + v[i]) * n[i];
    r.work += md.mass[I] * dvn * vbar_n;
    r.normal_force += md.mass[I] * dvn / dt_avg;
  }
  return r;
}

}  // namespace rk
