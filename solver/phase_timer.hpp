// Wall time per named phase of the step (the names solve.json and the log use).
#pragma once
#include <array>
#include <chrono>

namespace rk {

enum Phase { kDeformation, kStress, kTimeStep, kInternalForce, kExchange, kUpdate, kOutput, kReference, kPhaseCount };
inline constexpr std::array<const char*, kPhaseCount> kPhaseNames = {
    "deformation_gradient", "stress_update", "time_step", "internal_force", "overlap_exchange", "update", "output", "reference_update"};

class PhaseTimer {
 public:
  void start() { t0_ = std::chrono::steady_clock::now(); }
  void stop(Phase p) {
    const auto t1 = std::chrono::steady_clock::now();
    seconds[p] += std::chrono::duration<double>(t1 - t0_).count();
    t0_ = t1;
  }
  std::array<double, kPhaseCount> seconds{};

 private:
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace rk
