#include "chain.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

#include "error.hpp"
#include "stage_link.hpp"

namespace rk {

namespace {

// The collection rkpost wrote into CASE/vtk/case.pvd (write_pvd's layout).
std::vector<PvdEntry> read_pvd(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": not found; run rkpost on that stage first");
  static const std::regex row(R"re(<DataSet timestep="([^"]+)" part="(\d+)" name="([^"]*)" file="([^"]+)"/>)re");
  std::vector<PvdEntry> entries;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, row)) entries.push_back({std::stod(m[1]), std::stoi(m[2]), m[4], m[3]});
  }
  return entries;
}

}  // namespace

int write_chain_pvd(const std::string& case_dir, const std::vector<PvdEntry>& own) {
  namespace fs = std::filesystem;
  struct Stage {
    std::string dir;
    double end;  // where the next stage takes over on the chain's clock
  };
  std::vector<Stage> earlier;  // newest first
  StageLink link;
  for (std::string dir = case_dir; read_stage_link(dir, link); dir = link.from) {
    if (earlier.size() > 10000) throw Error(case_dir + "/stage.json: the chain of stages loops");
    earlier.push_back({link.from, link.start});
    if (!link.from_solve.empty() && solve_record_hash(link.from) != link.from_solve)
      std::fprintf(stderr,
                   "rkpost: warning: %s was solved or prepared again after %s started from it: the chain's frames "
                   "before %g s are not the run this stage went on from (solve the stages after it again)\n",
                   link.from.c_str(), dir.c_str(), link.start);
  }
  if (earlier.empty()) {  // no stage (any more: solved again without --from): an old chain would pass for its own
    fs::remove(case_dir + "/vtk/chain.pvd");
    return 0;
  }
  const fs::path vtk = fs::absolute(case_dir + "/vtk");
  std::map<std::string, int> parts = {{"part", 0}};  // a block's number by its name, over the chain
  std::vector<PvdEntry> chain;
  auto add = [&](const PvdEntry& e, const fs::path& folder) {
    const auto [at, added] = parts.try_emplace(e.name, int(parts.size()));
    chain.push_back({e.time, at->second, fs::relative(folder / e.file, vtk).string(), e.name});
  };
  for (auto s = earlier.rbegin(); s != earlier.rend(); ++s) {
    const fs::path folder = fs::absolute(s->dir + "/vtk");
    for (const PvdEntry& e : read_pvd((folder / "case.pvd").string()))
      if (e.time < s->end * (1 - 1e-12)) add(e, folder);  // the next stage's first frame shows its start
  }
  for (const PvdEntry& e : own) add(e, vtk);
  write_pvd(case_dir + "/vtk/chain.pvd", chain);
  return int(earlier.size()) + 1;
}

}  // namespace rk
