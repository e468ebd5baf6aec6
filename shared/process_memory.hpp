// This process's memory as Linux reports it (/proc/self/status), for prep.json and solve.json.
#pragma once
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace rk {

// MiB under `key`: "VmHWM:" the peak resident set so far, "VmRSS:" the resident set now (0 if absent).
inline double process_memory_mb(const char* key) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.compare(0, std::strlen(key), key) == 0) return std::strtod(line.c_str() + std::strlen(key), nullptr) / 1024.0;
  return 0;
}

}  // namespace rk
