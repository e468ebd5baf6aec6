// rksolve's driver: read this rank's subdomain, build the offline data, run the explicit loop.
#pragma once
#include <string>
#include <vector>

#include "parallel/comm.hpp"
#include "scene.hpp"

namespace rk {

struct SolveOptions {
  std::string case_dir;
  std::vector<Override> overrides;
  bool quiet = false;
  double progress_s = 0;  // seconds between progress lines; 0: 2 s on a terminal, 10 s otherwise
  bool restart = false;  // continue from CASE/checkpoint (time.end may be extended with --set)
  std::string from;      // a stage of a chain: start from this case's final state (stage.hpp)
};

void solve_case(const SolveOptions& options, const Comm& comm);

}  // namespace rk
