// CASE/report.md: what was run (scene, resolution, ranks), what it cost (wall time and its phases)
// and whether to trust it (energy balance verdict, final energies, die forces), in one page.
#pragma once
#include <string>

namespace rk {

void write_report(const std::string& case_dir);

}  // namespace rk
