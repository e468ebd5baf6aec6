#include "pictures.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace rk {
namespace {

// A path inside single quotes for the shell (a path holding a quote is not run).
bool quoted(const std::string& path, std::string& out) {
  if (path.find('\'') != std::string::npos) return false;
  out = "'" + path + "'";
  return true;
}

bool installed(const char* tool) { return std::system(("command -v " + std::string(tool) + " >/dev/null 2>&1").c_str()) == 0; }

}  // namespace

void make_pictures(const std::string& case_dir, bool quiet, bool renders) {
  namespace fs = std::filesystem;
  const std::string scripts = RK_SCRIPTS_DIR;
  std::string dir, py_plots, py_pictures, offscreen, log;
  fs::create_directories(case_dir + "/plots");
  if (!quoted(fs::absolute(case_dir).string(), dir) || !quoted(scripts + "/history_plots.py", py_plots) ||
      !quoted(scripts + "/pictures.py", py_pictures) || !quoted(scripts + "/pvbatch_offscreen.sh", offscreen) ||
      !quoted(fs::absolute(case_dir + "/plots/pictures.log").string(), log)) {
    std::fprintf(stderr, "rkpost: warning: no pictures: a path holds a quote (%s)\n", case_dir.c_str());
    return;
  }
  if (!fs::exists(scripts + "/pictures.py")) {
    std::fprintf(stderr, "rkpost: warning: no pictures: the scripts are not at %s\n", scripts.c_str());
    return;
  }
  std::system((": > " + log).c_str());
  if (fs::exists("/usr/bin/python3")) {  // Debian's python (matplotlib), not a pyenv one on PATH
    if (std::system(("/usr/bin/python3 " + py_plots + " " + dir + " >> " + log + " 2>&1").c_str()) != 0)
      std::fprintf(stderr, "rkpost: warning: the energy and force plots failed (see %s/plots/pictures.log)\n",
                   case_dir.c_str());
  } else {
    std::fprintf(stderr, "rkpost: warning: no plots: /usr/bin/python3 (with matplotlib) is not installed\n");
  }
  if (!renders) return;
  if (!installed("pvbatch")) {
    if (!quiet) std::printf("rkpost: no ParaView pictures (pvbatch not installed: python3-paraview)\n");
    return;
  }
  // off-screen under Xvfb when there is no display; a picture that hangs is stopped after 5 minutes
  const std::string render = std::getenv("DISPLAY") || !installed("xvfb-run") ? "pvbatch " : offscreen + " ";
  if (std::system(("timeout 300 " + render + py_pictures + " " + dir + " --frames 0,-1 >> " + log + " 2>&1").c_str()) != 0)
    std::fprintf(stderr, "rkpost: warning: the ParaView pictures failed (see %s/plots/pictures.log)\n", case_dir.c_str());
}

}  // namespace rk
