// The dies driven by their press (DieMotion::Ram; docs/scene.md, "Presses"): a hammer or a screw
// press brings blows of a given energy, a hydraulic press drives at its speed up to its force (and
// power) limit. The ram is a rigid mass M under the press's drive D and the reaction R of the whole
// part (force_factor x the modeled part's force along the motion), advanced with the part's central
// difference:
//   M (v^{n+1/2} - v^{n-1/2}) = dt_avg (D - R^n),   s^{n+1} = s^n + dt v^{n+1/2}
// - blow: D = 0. The ram meets the part at v0 = sqrt(2 eta E / M) and coasts until R stops it
//   (v^{n+1/2} <= 0: held at rest); the next blow starts from there at v0; after the last it stays.
// - hydraulic: D = force_limit, v^{n+1/2} kept in [0, min(speed, power_limit / R^n)]: the nominal
//   speed while the part needs less than the limit, slowed and stalled where it needs more. It stops
//   at its `stroke`, or stalls: its mean speed fell under 1 % of the nominal one over the time that
//   speed takes for a tenth of the smallest spacing.
// The run ends when every ram has stopped. R^n is summed over the ranks in fixed point
// (DieContact::reaction), so the rams move bitwise alike on any rank count. The energy a ram
// delivers, sum dt_avg R^n vbar, is for a blow exactly the kinetic energy it lost.
#pragma once
#include <string>
#include <vector>

#include "contact/die_contact.hpp"
#include "parallel/comm.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

class Presses {
 public:
  // h_min: the smallest spacing; headroom: the bits for every contact term of every rank
  Presses(const Scene& scene, double h_min, int headroom);
  bool empty() const { return rams_.empty(); }
  void start(State& st) const;  // each ram at rest stroke 0, at v0 or its nominal speed
  // Tells the contact where the driven dies are at t^n and how fast they move: v^{n-1/2} before
  // advance() (the friction's relative speed), the step's mean (vbar) after it (the work).
  void place(const State& st, DieContact& dies, bool stepped) const;
  // The largest |f . direction| of this rank's contacts with a driven die, for the fixed-point scale.
  double reaction_bound(const DieContact& dies) const;
  // v^{n+1/2} from the reactions R^n (collective: one sum over ranks), with `bound` the reduced
  // reaction_bound; the energy delivered.
  void advance(State& st, const DieContact& dies, double bound, double dt_avg, const Comm& comm);
  void move(State& st, double dt) const;  // s^{n+1}; whether each ram has stopped
  bool stopped(const State& st) const;    // every ram at rest for good: the run ends
  // A line per ram for the log and report.md: how it ended (blows, energy, stroke; a stalled press).
  std::vector<std::string> outcome(const State& st, const std::vector<Die>& dies) const;
  bool stalled(const State& st, std::size_t r) const;  // ram r, a hydraulic press, stopped short of its stroke

 private:
  struct Ram {
    std::size_t die;
    DieMotion::Ram press;
    double nominal;        // hydraulic: the motion's speed; blow: v0
    double force_factor;   // whole part / modeled part
    double vbar = 0;       // the last step's mean speed (not state: recomputed each step)
  };
  std::vector<Ram> rams_;
  std::vector<std::int64_t> sums_;  // per ram: this step's reaction in fixed point
  double h_min_;
  int headroom_ = 0;  // bits for every contact term of every rank
};

}  // namespace rk
