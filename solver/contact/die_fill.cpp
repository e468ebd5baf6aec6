#include "contact/die_fill.hpp"

#include <algorithm>
#include <cmath>

namespace rk {

DieFill::DieFill(const Model& md, const Scene& scene, const DieContact& dies, const Comm& comm) {
  double c[4] = {0, 0, 0, 0};  // the part's centre of mass at t = 0
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I])
      for (int i = 0; i < 3; ++i) c[i] += md.mass[I] * md.X[3 * I + i];
  for (std::size_t I = 0; I < md.n; ++I) c[3] += md.owned[I] ? md.mass[I] : 0.0;
  comm.sum(c, 4);
  for (std::size_t k = 0; k < md.dies.size(); ++k) {
    const DieSurface& s = md.dies[k];
    for (std::size_t t = 0; t < s.triangles.size() / 3; ++t) {
      const double* a = &s.vertices[3 * std::size_t(s.triangles[3 * t])];
      const double* b = &s.vertices[3 * std::size_t(s.triangles[3 * t + 1])];
      const double* d = &s.vertices[3 * std::size_t(s.triangles[3 * t + 2])];
      double n[3], toward = 0;  // (b - a) x (d - a): twice the area along the outward normal
      n[0] = (b[1] - a[1]) * (d[2] - a[2]) - (b[2] - a[2]) * (d[1] - a[1]);
      n[1] = (b[2] - a[2]) * (d[0] - a[0]) - (b[0] - a[0]) * (d[2] - a[2]);
      n[2] = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
      for (int i = 0; i < 3; ++i) toward += n[i] * (c[i] / c[3] - (a[i] + b[i] + d[i]) / 3);
      bool modeled = true;  // a corner on the part's side of every symmetry plane (within its round-off)
      for (const SymmetryPlane& p : scene.symmetry_planes) {
        double part = 0, side = -1e300;
        for (int i = 0; i < 3; ++i) part += (c[i] / c[3] - p.point[i]) * p.normal[i];
        for (const double* v : {a, b, d}) {
          double here = 0;
          for (int i = 0; i < 3; ++i) here += (v[i] - p.point[i]) * p.normal[i];
          side = std::max(side, here * (part < 0 ? -1.0 : 1.0));
        }
        modeled = modeled && side >= -1e-9 * std::abs(part);
      }
      area_.push_back(0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
      working_.push_back(toward > 0 && modeled);
    }
  }
  flags_.resize(working_.size());
  filled_.resize(md.dies.size());
  double terms = double(dies.terms());
  comm.sum(&terms, 1);
  headroom_ = headroom_bits(std::int64_t(terms) + 1);
}

const std::vector<double>& DieFill::filled(const DieContact& dies, const Comm& comm) {
  for (std::size_t t = 0; t < flags_.size(); ++t) flags_[t] = double(dies.touched()[t]);
  comm.max(flags_.data(), int(flags_.size()));
  for (std::size_t k = 0; k < filled_.size(); ++k) {
    double touched = 0, all = 0;
    for (std::size_t t = dies.triangle0(k); t < dies.triangle0(k + 1); ++t)  // a touched triangle is worked
      touched += flags_[t] * area_[t], all += working_[t] || flags_[t] > 0 ? area_[t] : 0.0;
    filled_[k] = all > 0 ? touched / all : 0.0;
  }
  return filled_;
}

DieFrame DieFill::frame(const DieContact& dies, double t, const Comm& comm) const {
  DieFrame f;
  for (std::size_t k = 0; k < dies.size(); ++k) f.stroke.push_back(dies.stroke(k, t));
  double bound = dies.surface_load_bound();
  comm.max(&bound, 1);
  const FixedScale scale = FixedScale::for_bound(bound, headroom_);
  f.load_scale = scale.to_double;
  dies.surface_loads(scale, f.load);
  f.touched = dies.touched();  // 1: touched; else 0 on the working surface, -1 off it
  for (std::size_t t = 0; t < f.touched.size(); ++t)
    if (f.touched[t] == 0 && !working_[t]) f.touched[t] = -1;
  return f;
}

}  // namespace rk
