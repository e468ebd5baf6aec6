// Folds and laps: where two parts of the free surface that were apart at t = 0 have come together
// (material flowing around and onto itself, the forging defect). Found by rkpost at each frame from
// the particles' positions: a surface particle is flagged when a surface particle facing it (their
// outward normals more than 120 degrees apart) is within kReach spacings of it now and was more than
// kApart spacings from it at t = 0 (the two surfaces closed in on each other; neighbours on one
// surface face the same way). The surface is the integration cells' faces that no other cell
// shares, less those on a symmetry plane. Flagged particles within two spacings of each other are
// one fold; a fold is reported once, at the first frame it shows, with where it is and how many
// particles it holds: a cluster holding a particle of a fold found at an earlier frame, or within
// kSame spacings of one, is that fold growing.
// The part's contact with itself (solver/contact/part_contact.hpp, `contact.self`) holds two such surfaces
// about 0.75 of their particles' spacing apart, so the reach is one spacing: the first frame that
// shows them there is the fold's time.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene.hpp"
#include "vtu_writer.hpp"

namespace rk {

struct Fold {
  double time = 0;                 // s, the first frame it shows in
  std::array<double, 3> at{};      // m, the centroid of its particles then
  std::size_t particles = 0;
};

class FoldFinder {
 public:
  static constexpr double kApart = 1.5;  // spacings apart at t = 0, at least
  static constexpr double kReach = 1.0;  // spacings apart now, at most
  static constexpr double kSame = 3;     // spacings from a fold's particles: the same fold
  // cells: the part's integration cells on the particles (global ids); X0: the particles at t = 0
  FoldFinder(const VtuCells& cells, const std::vector<double>& X0, double spacing,
             const std::vector<SymmetryPlane>& planes);
  // 1 for each particle on a fold at the current positions x, else 0; new folds appended to `found`
  // (the frames in order of time)
  std::vector<std::int64_t> find(const std::vector<double>& x, double time, std::vector<Fold>& found);

 private:
  std::vector<double> X0_;
  double h_;
  std::vector<std::array<std::int64_t, 5>> faces_;  // corners (the 4th -1 for a triangle), then a node of its cell off the face
  std::vector<std::int64_t> nodes_;                 // the surface particles
  std::vector<int> fold_of_;                        // per particle: the fold it was found on (-1: none yet)
};

// A line for report.md: where and when the fold showed, in mm and s.
std::string describe_fold(const Fold& fold);

}  // namespace rk
