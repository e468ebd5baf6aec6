// What the material does to the dies' surfaces: the contact loads on every triangle at a frame, and
// which triangles it has touched so far (DieContact keeps both per rank). A die's filled fraction is
// the touched share of its working surface, the triangles that face the part (outward normal toward
// the part's centre of mass at t = 0) reaching the modeled side of every symmetry plane (a corner there):
// a closed die's cavity within the modeled sector, a flat die's face, not its back or sides; a
// triangle the material touched counts as working surface whatever its side.
#pragma once
#include <cstdint>
#include <vector>

#include "contact/die_contact.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"

namespace rk {

// A frame's die datasets (shared/result_frame.hpp, kDieFrame*): every die's stroke; this rank's loads
// per triangle (normal force, tangential force on the die) in fixed point at a scale common to all
// ranks, so their sum over ranks is the same on any partition; per triangle 1 where its material has
// touched it, else 0 on the working surface and -1 off it (the same on every rank).
struct DieFrame {
  std::vector<double> stroke;
  double load_scale = 0;  // N per fixed-point unit
  std::vector<Fixed> load;
  std::vector<std::int64_t> touched;
};

class DieFill {
 public:
  // headroom: the bits for every contact term of every rank (the loads' fixed-point sums)
  DieFill(const Model& md, const Scene& scene, int headroom, const Comm& comm);
  // Collective: each die's filled fraction (its touched working area over its working area)
  const std::vector<double>& filled(const DieContact& dies, const Comm& comm);
  // Collective: the frame's die datasets at time t
  DieFrame frame(const DieContact& dies, double t, const Comm& comm) const;

 private:
  std::vector<double> area_;     // per triangle
  std::vector<bool> working_;    // per triangle: it faces the part (every touched triangle counts as well)
  std::vector<double> flags_, filled_;  // reduction buffer (per triangle), the fractions (per die)
  int headroom_ = 0;  // bits for every contact term of every rank
};

}  // namespace rk
