// A stage of a chain (rksolve CASE --from PREVIOUS): the case starts from the previous case's final
// state (its last checkpoint) with the same part, the same particles on the same ranks, and other
// dies or none.
//  - The chain has one clock: the stage's time.end counts from its start, the previous stage's end.
//  - A die of the previous stage (by name) with the same CAD, unit and motion continues: its place,
//    its motion's clock, its work and its fill go on. Any other die starts at its CAD position when
//    the stage starts. A die the stage leaves out is gone; the work it did stays in the balance.
//  - The part's essential conditions, symmetry planes and rigid walls are the previous stage's.
//  - A stage without dies, loads or moving faces is a dwell (a transfer, a rest in air): the part is
//    set down (its velocities zero) and only its temperature advances, at the thermal step; with
//    time.dwell off its motion goes on instead (an impact, a flight). A part set down while it still
//    moves (kinetic energy past 5 % of its internal) is warned of.
// A stage whose scene changes nothing continues the previous run bitwise.
#pragma once
#include <string>

#include "io/checkpoint.hpp"
#include "parallel/comm.hpp"
#include "scene.hpp"
#include "stage_link.hpp"

namespace rk {

// Collective: reads the previous case (its scene, its subdomain files, its newest checkpoint), checks
// that the part and its boundaries are the same, matches the dies by name and returns the link, with
// this rank's checkpoint of the previous case in `checkpoint` and what its dies carry over in
// `carry`. Throws rk::Error naming the case, the die or the key that does not match.
StageLink begin_stage(const std::string& from, const std::string& case_dir, const Scene& scene, const Comm& comm,
                      std::string& checkpoint, DieCarry& carry);

// The scene on the chain's clock: time.end from the stage's start, each die's motion from its start.
void apply_stage(const StageLink& link, Scene& scene);

}  // namespace rk
