// For the return-map tests of the rate-dependent laws (test_j2.cpp, test_flow_table.cpp): the
// largest gap between the returned stress and the law's flow stress over random states.
#pragma once
#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "material/j2_point.hpp"

inline double mises(const Eigen::Matrix3d& tau) {
  const Eigen::Matrix3d d = tau - tau.trace() / 3 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * d.squaredNorm());
}

// The largest relative gap over `count` random states (plastic strain, temperature and increment
// drawn by `draw` from three uniform numbers; stretches up to 1 %) between the returned von Mises
// stress and the law's flow stress at the increment's strain and rate; `plastic` counts the returns.
template <class Draw>
inline double worst_return(const rk::J2Params& law, unsigned seed, Draw draw, int& plastic, int count = 20000) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0;
  plastic = 0;
  for (int k = 0; k < count; ++k) {
    double cp[6] = {1, 1, 1, 0, 0, 0};
    double ep0, T, dt;
    const double a = u(gen), b = u(gen), c = u(gen);  // in this order: the states do not depend on the compiler
    draw(a, b, c, ep0, T, dt);
    const double s = 1 + 0.01 * std::pow(u(gen), 3);
    double ep = ep0;
    const Eigen::Matrix3d F = Eigen::Vector3d(s, 1 / std::sqrt(s), 1 / std::sqrt(s)).asDiagonal();
    const rk::J2Update up = rk::j2_update(F, law, cp, ep, T, dt);
    if (!up.plastic) continue;
    ++plastic;
    double flow, h, hr;
    law.flow(ep, (ep - ep0) / dt, T, flow, h, hr);
    worst = std::max(worst, std::abs(mises(up.tau) - flow) / flow);
  }
  return worst;
}

