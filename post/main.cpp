// rkpost: merge the ranks' result frames into one .vtu per frame and a .pvd time series.
//   rkpost CASE
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>

#include "cli.hpp"
#include "h5file.hpp"
#include "report.hpp"
#include "scene.hpp"
#include "subdomain.hpp"
#include "vtu_writer.hpp"

namespace fs = std::filesystem;

namespace {

struct Frame {
  double time = 0;
  std::vector<std::int64_t> gid, rank;
  std::vector<double> x, u, v, ep, vm, p;
};

void append(std::vector<double>& to, const std::vector<double>& from) { to.insert(to.end(), from.begin(), from.end()); }

// CASE/results/rank_NNNN/frame_FFFFF.h5 (one file per rank and frame, written whole or not at all)
std::string frame_file(const std::string& case_dir, int rank, int frame) {
  char name[64];
  std::snprintf(name, sizeof name, "/results/rank_%04d/frame_%05d.h5", rank, frame);
  return case_dir + name;
}

Frame read_frame(const std::string& case_dir, int ranks, int f) {
  Frame fr;
  char group[32];
  std::snprintf(group, sizeof group, "frames/%05d/", f);
  const std::string g(group);
  for (int r = 0; r < ranks; ++r) {
    const std::string path = frame_file(case_dir, r, f);
    if (!fs::exists(path)) throw rk::Error(path + ": missing (the rank did not write this frame)");
    const rk::H5File h(path, rk::H5File::Mode::read);
    fr.time = h.read<double>(g + "time")[0];
    auto gid = h.read<std::int64_t>(g + "global_id");
    fr.rank.insert(fr.rank.end(), gid.size(), std::int64_t(r));
    fr.gid.insert(fr.gid.end(), gid.begin(), gid.end());
    append(fr.x, h.read<double>(g + "x", 3));
    append(fr.u, h.read<double>(g + "displacement", 3));
    append(fr.v, h.read<double>(g + "velocity", 3));
    append(fr.ep, h.read<double>(g + "eq_plastic_strain"));
    append(fr.vm, h.read<double>(g + "von_mises"));
    append(fr.p, h.read<double>(g + "pressure"));
  }
  return fr;
}

// Reorders by global id and checks that every particle appears exactly once.
void sort_by_global_id(Frame& fr, const std::string& where) {
  const std::size_t n = fr.gid.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return fr.gid[a] < fr.gid[b]; });
  for (std::size_t k = 0; k < n; ++k)
    if (fr.gid[order[k]] != std::int64_t(k))
      throw rk::Error(where + ": particles are missing or duplicated across ranks (global id " +
                      std::to_string(fr.gid[order[k]]) + " at position " + std::to_string(k) + ")");
  auto permute = [&](auto& a, int w) {
    auto b = a;
    for (std::size_t k = 0; k < n; ++k)
      for (int c = 0; c < w; ++c) a[w * k + c] = b[w * order[k] + c];
  };
  permute(fr.gid, 1), permute(fr.rank, 1), permute(fr.x, 3), permute(fr.u, 3), permute(fr.v, 3);
  permute(fr.ep, 1), permute(fr.vm, 1), permute(fr.p, 1);
}

int run(int argc, char** argv) {
  CLI::App app{"rkpost: merge the ranks' results into VTK files for ParaView (CASE/vtk/case.pvd)", "rkpost"};
  rk::add_version_flag(app);
  std::string case_dir;
  bool quiet = false;
  app.add_option("case", case_dir, "case directory (after rksolve)")->required();
  app.add_flag("--quiet", quiet, "print nothing but errors");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  std::ifstream prep_file(case_dir + "/prep.json");
  if (!prep_file) throw rk::Error(case_dir + "/prep.json: not found (is this a case directory written by rkprep?)");
  const int ranks = nlohmann::json::parse(prep_file)["ranks"].get<int>();
  std::int64_t frames = 0;  // the highest frame any rank wrote, plus one
  for (int r = 0; r < ranks; ++r) {
    const std::string dir = fs::path(frame_file(case_dir, r, 0)).parent_path().string();
    if (!fs::is_directory(dir)) throw rk::Error(dir + ": not found (has rksolve run on this case?)");
    for (const auto& entry : fs::directory_iterator(dir)) {
      long long k = -1;
      const std::string file = entry.path().filename().string();
      if (std::sscanf(file.c_str(), "frame_%lld.h5", &k) == 1 && !file.ends_with(".tmp"))
        frames = std::max<std::int64_t>(frames, k + 1);
    }
  }
  fs::create_directories(case_dir + "/vtk");
  // the dies, placed at their stroke at each frame's time (a part of their own in the .pvd)
  const rk::Scene scene = rk::load_scene(case_dir + "/scene.resolved.yaml", {}, rk::Side::solve);
  std::vector<rk::DieSurface> dies;
  if (!scene.dies.empty())
    dies = rk::read_subdomain(rk::subdomain_path(case_dir, 0), 0, ranks, scene.prep_hash).dies;
  std::vector<rk::PvdEntry> index;
  int skipped = 0;
  for (int f = 0; f < frames; ++f) {
    Frame fr;
    try {  // a frame missing on a rank or half written is reported and skipped; the rest is merged
      fr = read_frame(case_dir, ranks, f);
      sort_by_global_id(fr, case_dir + " frame " + std::to_string(f));
    } catch (const rk::Error& e) {
      std::fprintf(stderr, "rkpost: frame %d skipped: %s\n", f, e.what());
      ++skipped;
      continue;
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.vtu", f);
    std::vector<rk::VtuArray> data;
    data.push_back({"global_id", 1, {}, fr.gid});
    data.push_back({"displacement", 3, fr.u, {}});
    data.push_back({"velocity", 3, fr.v, {}});
    data.push_back({"eq_plastic_strain", 1, fr.ep, {}});
    data.push_back({"von_mises", 1, fr.vm, {}});
    data.push_back({"pressure", 1, fr.p, {}});
    data.push_back({"rank", 1, {}, fr.rank});
    rk::write_vtu(case_dir + "/vtk/" + name, fr.x, data);
    index.push_back({fr.time, 0, name});
    for (std::size_t k = 0; k < dies.size(); ++k) {
      const auto& die = scene.dies[k];
      std::vector<double> x = dies[k].vertices;
      const double stroke = die.motion.stroke(fr.time);
      for (std::size_t v = 0; v < x.size(); ++v) x[v] += stroke * die.motion.direction[v % 3];
      char file[160];
      std::snprintf(file, sizeof file, "die_%s_%05d.vtu", die.name.c_str(), f);
      rk::write_vtu(case_dir + "/vtk/" + file, x, {}, dies[k].triangles);
      index.push_back({fr.time, int(k + 1), file});
    }
  }
  rk::write_pvd(case_dir + "/vtk/case.pvd", index);
  rk::write_report(case_dir);
  if (!quiet)
    std::printf("rkpost: %lld frames of %d ranks merged into %s/vtk/case.pvd (%d skipped, %zu dies)\n",
                static_cast<long long>(frames - skipped), ranks, case_dir.c_str(), skipped, dies.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return rk::guarded_main("rkpost", [&] { return run(argc, argv); }); }
