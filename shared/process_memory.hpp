// This process's memory as Linux reports it (/proc/self/status), for prep.json and solve.json, and the
// machine's available memory (/proc/meminfo).
#pragma once
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace rk {

// MiB under `key` (its value in kB) in a file of "Key: value kB" lines (0 if absent).
inline double proc_memory_mb(const char* file, const char* key) {
  std::ifstream status(file);
  for (std::string line; std::getline(status, line);)
    if (line.compare(0, std::strlen(key), key) == 0) return std::strtod(line.c_str() + std::strlen(key), nullptr) / 1024.0;
  return 0;
}

// "VmHWM:" the peak resident set so far, "VmRSS:" the resident set now.
inline double process_memory_mb(const char* key) { return proc_memory_mb("/proc/self/status", key); }

// The memory the machine can give without swapping now (MemAvailable; 0 where unknown).
inline double available_memory_mb() { return proc_memory_mb("/proc/meminfo", "MemAvailable:"); }

}  // namespace rk
