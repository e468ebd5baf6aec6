// A case folder's entries and which program writes them: rkprep (the subdomains, prep.json, the
// resolved scene), rksolve (results/, checkpoint/, history.csv, solve.json, stage.json), rkpost (vtk/, plots/,
// report.md). A new rkprep output replaces all of them, so that no result of another case survives
// beside the new subdomains.
#pragma once
#include <array>
#include <filesystem>
#include <string>

namespace rk {

// the lock of the program writing the case, rksolve or rkprep (case_lock.hpp; removed at its end, left by a
// killed run)
inline constexpr const char* kSolveLock = ".rksolve.lock";

inline constexpr std::array<const char*, 12> kCaseEntries = {
    "sub", "prep.json", "scene.resolved.yaml",                                 // rkprep
    "results", "checkpoint", "history.csv", "solve.json", "stage.json", kSolveLock,  // rksolve
    "vtk", "plots", "report.md"};                                              // rkpost

// The entries of kCaseEntries present in `dir`, comma-separated ("" when none, or no such folder).
inline std::string case_entries_in(const std::filesystem::path& dir) {
  std::string found;
  for (const char* e : kCaseEntries)
    if (std::filesystem::exists(dir / e)) found += (found.empty() ? "" : ", ") + std::string(e);
  return found;
}

}  // namespace rk
