// Multi-rate steps (subcycling, time.subcycling = 2^K): where the part's cells allow it, a particle takes
// a step 2^k times the smallest (k <= K), so the points around it are updated 2^k times less often.
// The steps go in cycles of 2^L smallest steps dt (L <= K; shorter where a cycle would pass the next
// output or the end), planned at the cycle's first step, when every point is fresh:
// - cell c's own stable step dt_c (time_step.hpp) limits the cells around it to class
//   L_c = the largest k <= L with 2^k dt <= dt_c;
// - particle I takes class c_I = the least L_c over the cells whose points' rows hold it (over all
//   ranks: the shared particles' classes are summed as counts in fixed point, so every copy agrees);
// - a cell takes the least class of the particles in its points' rows.
// At offset o in the cycle the classes k with 2^k dividing o are due (all at o = 0). A due cell's points
// are gathered, updated and scattered; a due particle's velocity takes its internal force over its own
// step, v += dt_avg_I (g - f_I / m_I), dt_avg_I = (the last span of I + 2^{c_I} dt) / 2; every
// particle moves every step, u += dt v, so a slower particle moves along its straight path in between
// (the linear interpolation of Belytschko, Yen and Mullen's mixed time integration, 1979). The
// force on a due particle is complete: every point whose row holds it has a class no larger than its
// own. Contact and the essential BCs act on every particle at every step (dt), as without subcycling,
// and a particle that met a contact in the last cycle takes the smallest step in the next: a slower one
// would meet the die's penalty at every step and its own material's push once a span, a sawtooth in
// the contact force (the die's work the same, its force at a cycle's start 1-6 % low).
// Why and what was measured: docs/decisions.md, "Multi-rate steps".
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "model.hpp"
#include "parallel/fixed_point.hpp"

namespace rk {

class Subcycles {
 public:
  static constexpr int kMaxLevels = 4;  // classes 0 .. 4: steps up to 16 dt

  Subcycles(const Model& md, int max_ratio);

  // Whether `step` begins a cycle (the first step of a run does): every point and particle is due,
  // and a checkpoint, frame or history row may be written.
  bool starts(std::int64_t step) const { return start_ < 0 || step - start_ >= (std::int64_t(1) << levels_); }
  int max_levels() const { return max_levels_; }

  // At a cycle's first step: dt_cell each cell's stable step, as far as its class needs (time_step.hpp,
  // cell_time_steps), dt the smallest step, 2^levels of them the cycle. The particles that took a
  // contact force in the last cycle (touched) take the smallest step. The cycle is as long as its
  // largest class needs (2^levels at most); with levels 0 (every cell at the smallest step) nothing is
  // counted, dt_cell is not read and nothing collective is called. `sum` adds the other ranks' counts of
  // the shared particles (kForceStride per particle, OverlapExchange::sum), `largest` the largest over
  // the ranks (collective both).
  using SumOverRanks = std::function<void(std::vector<Fixed>&)>;
  using LargestOverRanks = std::function<int(int)>;
  void plan(const Model& md, const std::vector<double>& dt_cell, double dt, int levels, std::int64_t step,
            const SumOverRanks& sum, const LargestOverRanks& largest);
  // After a step's contact: marks the particles with a contact force (3 per particle) for the next plan.
  void touch(const std::vector<double>& contact_force);

  // The classes due at `step` (a particle or cell is due when its class is at most this).
  int level(std::int64_t step) const;
  std::span<const std::int32_t> all_cells() const { return all_cells_; }
  // The due cells and points at `level`, in class order.
  std::span<const std::int32_t> cells(int level) const { return {cells_.data(), cells_end_[std::size_t(level)]}; }
  std::span<const std::int32_t> boundary_points(int level) const { return {boundary_.data(), boundary_end_[std::size_t(level)]}; }
  std::span<const std::int32_t> interior_points(int level) const { return {interior_.data(), interior_end_[std::size_t(level)]}; }
  int particle_class(std::size_t I) const { return particle_class_[I]; }

 private:
  int max_levels_;
  std::int64_t start_ = -1;
  int levels_ = 0;
  std::vector<std::int32_t> point_cell_;
  std::vector<std::int64_t> support_offsets_;  // cell c's particles: support_[support_offsets_[c] ..)
  std::vector<std::int32_t> support_;
  std::vector<std::int8_t> particle_class_, cell_class_, touched_;
  std::vector<Fixed> counts_;  // the classes' counts per particle (kForceStride), summed over ranks
  std::vector<std::int32_t> all_cells_;
  std::vector<std::int32_t> cells_, boundary_, interior_;  // sorted by class
  std::vector<std::size_t> cells_end_, boundary_end_, interior_end_;  // per level: the due entries
};

}  // namespace rk
