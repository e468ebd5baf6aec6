// gmsh is a process-wide singleton: one session per CAD file read, with the spacing given to .geo
// scripts as the number `h` (like `gmsh -setnumber h ...`) and gmsh's log kept for error messages.
#pragma once
#include <gmsh.h>

#include <cstdio>
#include <string>
#include <vector>

namespace rk {

struct GmshSession {
  explicit GmshSession(double h) {
    char hs[32];
    std::snprintf(hs, sizeof hs, "%.17g", h);
    std::vector<std::string> args{"rkprep", "-setnumber", "h", hs};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    gmsh::initialize(int(argv.size()), argv.data(), false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 2);
    gmsh::logger::start();
  }
  // gmsh's own error lines, for messages when it failed without throwing.
  static std::string errors() {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string out;
    for (auto& l : log)
      if (l.rfind("Error", 0) == 0) out += (out.empty() ? "" : "; ") + l;
    return out;
  }
  ~GmshSession() { gmsh::finalize(); }
};


}  // namespace rk
