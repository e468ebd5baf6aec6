// What every program does the same way: --version, --set parsing, and turning an error into one
// clear message with a non-zero exit.
#pragma once
#include <CLI/CLI.hpp>

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

// main() of a serial program: runs `run`, turning any error into one message and exit status 1.
template <class Run>
int guarded_main(const char* program, Run run) {
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
