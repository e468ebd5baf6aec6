// A chain of stages (rksolve CASE --from PREVIOUS, CASE/stage.json) as one sequence in ParaView:
// CASE/vtk/chain.pvd lists every earlier stage's frames up to the next stage's start, then this
// case's, on the chain's one clock; blocks keep their names over the chain (the part, each die).
#pragma once
#include <string>
#include <vector>

#include "vtu_writer.hpp"

namespace rk {

// Writes CASE/vtk/chain.pvd when CASE is a stage and returns the number of stages in it (0 when CASE
// is not a stage). `own`: this case's collection, as written to its case.pvd. An earlier stage
// whose vtk/case.pvd is missing is an rk::Error asking to run rkpost on it first.
int write_chain_pvd(const std::string& case_dir, const std::vector<PvdEntry>& own);

}  // namespace rk
