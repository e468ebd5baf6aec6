// CASE/stage.json: a case that is a stage of a chain (rksolve CASE --from PREVIOUS) names the case it
// continues and where on the chain's clock it starts. rksolve writes it at the stage's start and reads
// it back on --restart; rkpost follows the links to draw the chain as one sequence (vtk/chain.pvd).
#pragma once
#include <string>
#include <vector>

namespace rk {

struct StageLink {
  std::string from;                 // the previous stage's case folder (absolute; read: the one beside
                                    // this case where the chain was moved or copied whole)
  double start = 0;                 // s: the previous stage's end, this one's start on the chain's clock
  std::vector<double> die_start;    // per die of this stage's scene: when its motion began (s)
  std::vector<int> continues;       // per die: the previous stage's die it continues, or -1 (new)
  bool dwell = false;               // no dies, loads or moving faces: only the temperature advanced
  // the previous stage's solve.json as this stage started from it (a hash): a previous stage solved or
  // prepared again since then no longer holds the state this one started from ("" in older links)
  std::string from_solve;
};

// The hash of CASE/solve.json ("" when it cannot be read), as StageLink::from_solve records it.
std::string solve_record_hash(const std::string& case_dir);

inline const char* kStageLinkFile = "stage.json";

void write_stage_link(const std::string& case_dir, const StageLink& link);
// false when CASE has no stage.json (a case that is not a stage); throws rk::Error naming a damaged one
bool read_stage_link(const std::string& case_dir, StageLink& link);

}  // namespace rk
