// A case folder's entries and which program writes them: rkprep (the subdomains, prep.json, the
// resolved scene), rksolve (results/, checkpoint/, history.csv, solve.json, stage.json), rkpost (vtk/, plots/,
// report.md). A new rkprep output replaces all of them, so that no result of another case survives
// beside the new subdomains.
#pragma once
#include <array>
#include <filesystem>
#include <string>

namespace rk {

inline constexpr std::array<const char*, 11> kCaseEntries = {
    "sub", "prep.json", "scene.resolved.yaml",                    // rkprep
    "results", "checkpoint", "history.csv", "solve.json", "stage.json",  // rksolve
    "vtk", "plots", "report.md"};                                 // rkpost

// The entries of kCaseEntries present in `dir`, comma-separated ("" when none, or no such folder).
inline std::string case_entries_in(const std::filesystem::path& dir) {
  std::string found;
  for (const char* e : kCaseEntries)
    if (std::filesystem::exists(dir / e)) found += (found.empty() ? "" : ", ") + std::string(e);
  return found;
}

}  // namespace rk
