// Wall time per phase of the step (shared/phase_names.hpp: the names solve.json uses).
#pragma once
#include <array>
#include <chrono>

#include "phase_names.hpp"

namespace rk {

class PhaseTimer {
 public:
  void start() { t0_ = std::chrono::steady_clock::now(); }
  void stop(Phase p) {  // the time since the last start or stop is p's
    const auto t1 = std::chrono::steady_clock::now();
    seconds[p] += std::chrono::duration<double>(t1 - t0_).count();
    t0_ = t1;
  }
  std::array<double, kPhaseCount> seconds{};

 private:
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace rk
