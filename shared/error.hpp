// One exception type for every input boundary: the message names the file, key, line or particle.
#pragma once
#include <filesystem>
#include <stdexcept>
#include <string>

namespace rk {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An input file that must be there: "PATH: WHAT not found", or "PATH: a folder, not a WHAT" (a folder
// reads as an empty or unreadable file further on, with a message about its contents).
inline void require_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": a folder, not a " + what);
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": " + what + " not found");
}

}  // namespace rk
