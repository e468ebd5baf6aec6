#include "contact/die_fill.hpp"

#include <algorithm>
#include <cmath>

namespace rk {

DieFill::DieFill(const Model& md, const Scene& scene, int headroom, const Comm& comm) : headroom_(headroom) {
  double c[4] = {0, 0, 0, 0};  // the part's centre of mass at t = 0
  for (std::size_t I = 0; I < md.n; ++I)
    if (md.owned[I])
      for (int i = 0; i < 3; ++i) c[i] += md.mass[I] * md.X[3 * I + i];
  for (std::size_t I = 0; I < md.n; ++I) c[3] += md.owned[I] ? md.mass[I] : 0.0;
  comm.sum(c, 4);
  for (std::size_t k = 0; k < md.dies.size(); ++k) {
    const DieSurface& s = md.dies[k];
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
      double n[3], centre[3], toward = 0;
      area_.push_back(s.area_normal(t, n));
      s.centre(t, centre);
      for (int i = 0; i < 3; ++i) toward += n[i] * (c[i] / c[3] - centre[i]);
      bool modeled = true;  // a corner on the part's side of every symmetry plane (within its round-off)
      for (const SymmetryPlane& p : scene.symmetry_planes) {
        double part = 0, side = -1e300;
        for (int i = 0; i < 3; ++i) part += (c[i] / c[3] - p.point[i]) * p.normal[i];
        for (int q = 0; q < 3; ++q) {
          const double* v = s.corner(t, q);
          double here = 0;
          for (int i = 0; i < 3; ++i) here += (v[i] - p.point[i]) * p.normal[i];
          side = std::max(side, here * (part < 0 ? -1.0 : 1.0));
        }
        modeled = modeled && side >= -1e-9 * std::abs(part);
      }
      working_.push_back(toward > 0 && modeled);
    }
  }
  flags_.resize(working_.size());
  filled_.resize(md.dies.size());
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
