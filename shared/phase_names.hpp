// The phases of rksolve's step, in the order the step runs them (solver/solver.cpp, Simulation::run):
// each is a function of that name, timed under it; solve.json's `phases` and rkpost's report use
// these names.
#pragma once
#include <array>

namespace rk {

enum Phase {
  kReferenceUpdate, kCheckpoint, kDeformationGradient, kStressUpdate, kContact, kTimeStep, kHeatTransfer, kInternalForce,
  kOverlapExchange, kVelocityUpdate, kPress, kConstraints, kBoundaryWork, kHistory, kOutput, kDisplacementUpdate, kPhaseCount
};
inline constexpr std::array<const char*, kPhaseCount> kPhaseNames = {
    "reference_update", "checkpoint", "deformation_gradient", "stress_update", "contact",
    "time_step", "heat_transfer", "internal_force", "overlap_exchange", "velocity_update", "press", "constraints",
    "boundary_work", "history", "output", "displacement_update"};

}  // namespace rk
