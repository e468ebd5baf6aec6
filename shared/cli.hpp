// What every program does the same way: --version, --set parsing, and turning an error into one
// clear message with a non-zero exit.
#pragma once
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "error.hpp"
#include "rkforge/version.hpp"
#include "scene.hpp"

namespace rk {

inline void add_version_flag(CLI::App& app) {
  app.set_version_flag("--version", std::string(app.get_name()) + " (rkforge) " + kVersion);
}

inline std::vector<Override> parse_overrides(const std::vector<std::string>& sets) {
  std::vector<Override> out;
  for (const auto& s : sets) out.push_back(parse_override(s));
  return out;
}

// A write past the file-size limit (ulimit -f) fails with EFBIG, which the writers report by file, instead of
// SIGXFSZ killing the program without a word (and leaving a half-written file and the case's lock)
inline void ignore_file_size_signal() { std::signal(SIGXFSZ, SIG_IGN); }

// main() of a serial program: runs `run`, turning any error into one message and exit status 1.
template <class Run>
int guarded_main(const char* program, Run run) {
  ignore_file_size_signal();
  try {
    return run();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
  } catch (const std::filesystem::filesystem_error& e) {  // a folder or file the system refused: named, with why
    std::fprintf(stderr, "%s: error: %s: %s\n", program, e.path1().c_str(), e.code().message().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", program, e.what());
  }
  return 1;
}

}  // namespace rk
