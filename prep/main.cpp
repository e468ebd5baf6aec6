// rkprep: scene + CAD -> particles, integration cells, METIS partition, one subdomain file per rank.
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string_view>

#include "cad_mesh.hpp"
#include "case_layout.hpp"
#include "case_lock.hpp"
#include "cli.hpp"
#include "die_surface.hpp"
#include "discretize.hpp"
#include "jitter.hpp"
#include "partition.hpp"
#include "process_memory.hpp"
#include "scene.hpp"
#include "subdomain.hpp"
#include "text_file.hpp"

namespace fs = std::filesystem;

namespace {

class PhaseTimer {  // wall time per named phase, for prep.json and the progress lines
 public:
  explicit PhaseTimer(bool quiet) : quiet_(quiet) {}
  template <class Fn>
  auto run(const std::string& name, Fn fn) {
    if (!quiet_) std::printf("rkprep: %-12s ...", name.c_str()), std::fflush(stdout);
    auto t0 = std::chrono::steady_clock::now();
    struct EndLine {  // a phase that throws ends its progress line, so that the error starts its own
      bool quiet, done = false;
      ~EndLine() {
        if (!quiet && !done) std::printf(" stopped\n"), std::fflush(stdout);
      }
    } end_line{quiet_};
    auto result = fn();
    end_line.done = true;
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    phases_[name] = s;
    if (!quiet_) std::printf(" %.3f s\n", s), std::fflush(stdout);  // (before a warning on stderr)
    return result;
  }
  nlohmann::json json() const { return phases_; }

 private:
  bool quiet_;
  nlohmann::json phases_ = nlohmann::json::object();
};

void print_partition(const nlohmann::json& report) {
  std::printf("%6s %9s %9s %9s %9s %10s  %s\n", "rank", "cells", "points", "owned", "overlap", "exchanged",
              "neighbours");
  for (const auto& r : report["ranks"]) {
    std::string nb;
    for (const auto& q : r["neighbour_ranks"]) {
      if (!nb.empty()) nb += ',';
      nb += std::to_string(q.get<int>());
    }
    std::printf("%6d %9zu %9zu %9zu %9zu %10zu  %s\n", r["rank"].get<int>(), r["cells"].get<std::size_t>(),
                r["integration_points"].get<std::size_t>(), r["owned_particles"].get<std::size_t>(),
                r["overlap_particles"].get<std::size_t>(), r["values_exchanged_per_step"].get<std::size_t>(),
                nb.c_str());
  }
  std::printf("imbalance %.3f (max/mean points), overlap fraction %.3f, %zu values exchanged per step\n",
              report["imbalance"].get<double>(), report["overlap_fraction"].get<double>(),
              report["values_exchanged_per_step"].get<std::size_t>());
}

// The case folder takes files, checked before any meshing is spent: the folder is made (only the
// folder: an empty sub/ would read as a case already) and a file is written in it and removed.
void check_case_folder_writable(const fs::path& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw rk::Error(out.string() + ": cannot create the case folder (" + ec.message() + "); choose another --out");
  const fs::path probe = out / ".rkprep_write_check";
  errno = 0;
  std::FILE* f = std::fopen(probe.c_str(), "w");
  int err = f ? 0 : (errno ? errno : EIO);
  if (f) {
    if (std::fputs("rkprep\n", f) < 0) err = errno ? errno : EIO;
    if (std::fclose(f) != 0 && !err) err = errno ? errno : EIO;
    fs::remove(probe, ec);
  }
  if (err)
    throw rk::Error(out.string() + ": cannot write in the case folder (" + std::strerror(err) +
                    "); choose another --out");
}

int run(int argc, char** argv) {
  CLI::App app{"rkprep: build particles, integration cells and per-rank subdomain files from a scene", "rkprep"};
  rk::add_version_flag(app);
  std::string scene_file, out, partitioner = "metis-kway";
  int ranks = 1;
  bool quiet = false;
  std::vector<std::string> sets;
  app.add_option("scene", scene_file, "scene YAML file")->required();
  app.add_option("--ranks", ranks, "number of MPI ranks (one subdomain file each)")
      ->check(CLI::Validator(
          [](std::string& v) {
            try {
              std::size_t used = 0;
              if (std::stoi(v, &used) >= 1 && used == v.size()) return std::string();
            } catch (const std::exception&) {
            }
            return v + " is not a number of ranks (a whole number, at least 1)";
          },
          "RANKS >= 1"));
  app.add_option("--out", out, "case directory to write")->required();
  app.add_option("--set", sets, "override a scene key: key.path=value (repeatable)");
  app.add_option("--partitioner", partitioner, "metis-kway | metis-recursive")
      ->check(CLI::IsMember({"metis-kway", "metis-recursive"}));
  app.add_flag("--quiet", quiet, "print nothing but errors");
  bool force = false;
  app.add_flag("--force", force, "replace the files of a case already in --out (its results, history, checkpoints)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  PhaseTimer timer(quiet);
  auto t0 = std::chrono::steady_clock::now();
  const rk::Scene scene = rk::load_scene(scene_file, rk::parse_overrides(sets), rk::Side::prep);
  check_case_folder_writable(out);
  std::fflush(stdout);
  for (const std::string& w : rk::scene_warnings(scene)) std::fprintf(stderr, "rkprep: warning: %s\n", w.c_str());
  // a new case never lies beside another's results: refused, or with --force those files go first;
  // never under a running rksolve (the lock, held to the end of the prep)
  const std::string old = rk::case_entries_in(out);
  const rk::CaseLock lock(out);
  if (!old.empty()) {
    if (!force)
      throw rk::Error(out + ": holds a case already (" + old +
                      "); choose another --out, or pass --force to replace that case's files");
    for (const char* e : rk::kCaseEntries)
      if (std::string_view(e) != rk::kSolveLock) fs::remove_all(fs::path(out) / e);  // (the lock: this one's now)
  }
  const double dilation = scene.discretization.dilation;
  rk::VolumeMesh mesh = timer.run("mesh", [&] {
    rk::VolumeMesh m = rk::mesh_cad({scene.geometry.cad, scene.geometry.unit, scene.discretization.spacing, dilation});
    std::vector<std::string> names{"part"};
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      rk::append_body(m, rk::mesh_cad({scene.bodies[b].cad, scene.bodies[b].unit, scene.discretization.spacing, dilation}), int(b + 1));
      names.push_back(scene.bodies[b].name);
    }
    rk::check_bodies_apart(m, names, scene.discretization.spacing);
    return m;
  });
  const rk::Discretization disc =
      timer.run("discretize", [&] {
        rk::Discretization d = rk::discretize(mesh, scene.discretization.gauss_order, scene.discretization.cell_rule);
        if (scene.discretization.integration == "nodal") rk::use_nodal_points(mesh, d);
        return d;
      });
  const auto dies = timer.run("dies", [&] {
    std::vector<rk::DieSurface> out;
    for (const auto& die : scene.dies) {
      out.push_back(rk::mesh_die(die, scene.discretization.spacing));
      rk::check_workpiece_outside(out.back(), die, mesh, scene.discretization.spacing);
      rk::check_die_off_symmetry_planes(out.back(), die, scene.symmetry_planes, mesh, scene.discretization.spacing);
    }
    return out;
  });
  const auto cell_rank = timer.run("partition", [&] { return rk::partition_cells(mesh, disc, ranks, partitioner); });
  // the particles are the mesh nodes, moved when the scene asks for an irregular layout (after the
  // integration points and volumes were taken from the mesh, so those stay)
  rk::jitter_interior(mesh, disc.spacing, scene.discretization.jitter);
  const auto subs = timer.run("subdomains", [&] {
    return rk::build_subdomains({mesh, disc, cell_rank, ranks, scene.discretization.dilation, scene.prep_hash, dies});
  });
  const auto report = rk::partition_report(subs, mesh.node_count());
  timer.run("write", [&] {
    fs::create_directories(fs::path(out) / "sub");
    for (const auto& s : subs) rk::write_subdomain(rk::subdomain_path(out, int(s.rank)), s);
    rk::write_text_file((fs::path(out) / "scene.resolved.yaml").string(), scene.resolved_yaml);
    return 0;
  });

  // the spacing the mesh achieved against the one asked (a CAD's small features or an STL's facets
  // refine the mesh). The shipped O-grid cylinders read 0.67-0.74 of it (their core and radial edges
  // are 2/pi of the rim's), so only a mesh off by more than half is suspicious.
  const double achieved = rk::median_edge(mesh);
  const bool off = !(std::abs(achieved / scene.discretization.spacing - 1) <= 0.5);
  std::fflush(stdout);  // (the progress lines before the warning, where both go to one file)
  if (off)
    std::fprintf(stderr,
                 "rkprep: warning: the mesh's median cell edge is %.3g m against discretization.spacing = %.3g m "
                 "(%+.0f %%): the CAD's features or faceting set the mesh; check the particle count and run time\n",
                 achieved, scene.discretization.spacing, 100 * (achieved / scene.discretization.spacing - 1));
  double total_volume = 0;
  for (double v : disc.volume) total_volume += v;
  std::size_t surface = 0;
  for (auto f : mesh.surface) surface += f;
  nlohmann::json prep = {
      {"version", rk::kVersion},
      {"scene", fs::absolute(scene_file).string()},
      {"scene_hash", scene.prep_hash},
      {"ranks", ranks},
      {"partitioner", ranks > 1 ? partitioner : "none"},
      {"particles", mesh.node_count()},
      {"surface_particles", surface},
      {"cells", mesh.cell_count()},
      {"integration_points", disc.point_weight.size()},
      {"volume_m3", total_volume},
      {"spacing_m", scene.discretization.spacing},
      {"spacing_achieved_m", achieved},
      {"phases_s", timer.json()},
      {"wall_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()},
      {"peak_memory_mb", rk::process_memory_mb("VmHWM:")},
      {"partition", report}};
  rk::write_text_file((fs::path(out) / "prep.json").string(), prep.dump(2) + "\n");
  if (!quiet) {
    std::printf("rkprep: %zu particles (%zu on the surface), %zu cells, %zu integration points, volume %.6g m^3, "
                "spacing %.4g m (median cell edge; asked %.4g m)\n",
                mesh.node_count(), surface, mesh.cell_count(), disc.point_weight.size(), total_volume, achieved,
                scene.discretization.spacing);
    print_partition(report);
    std::printf("rkprep: wrote %s/sub/rank_*.h5 (%d files), prep.json, scene.resolved.yaml\n", out.c_str(), ranks);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return rk::guarded_main("rkprep", [&] { return run(argc, argv); }); }
