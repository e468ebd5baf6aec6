#include "stage.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "error.hpp"
#include "h5file.hpp"
#include "subdomain.hpp"

namespace rk {

namespace {

bool same_motion(const DieMotion& a, const DieMotion& b) {
  const auto& c = a.crank;
  const auto& d = b.crank;
  const auto& r = a.ram;
  const auto& s = b.ram;
  return a.direction == b.direction && a.speed == b.speed && a.curve.points() == b.curve.points() &&
         c.radius == d.radius && c.rod == d.rod && c.strokes_per_minute == d.strokes_per_minute &&
         c.start_angle == d.start_angle && r.mass == s.mass && r.energy == s.energy && r.efficiency == s.efficiency &&
         r.blows == s.blows && r.force_limit == s.force_limit && r.power_limit == s.power_limit && r.stroke == s.stroke;
}

bool same_faces(const std::vector<EssentialFace>& a, const std::vector<EssentialFace>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].point != b[k].point || a[k].normal != b[k].normal || !same_motion(a[k].motion, b[k].motion)) return false;
  return true;
}

// The boundaries that act on the part's displacement from the chain's start: they cannot change
// between stages (a face held from t = 0 would pull the formed part back).
void check_boundaries(const Scene& now, const Scene& before, const std::string& from) {
  auto same_planes = [](const auto& a, const auto& b) {  // symmetry planes or rigid walls: point and normal
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const auto& p, const auto& q) {
             return p.point == q.point && p.normal == q.normal;
           });
  };
  const char* what = nullptr;
  if (!same_planes(now.symmetry_planes, before.symmetry_planes) || !same_planes(now.rigid_walls, before.rigid_walls))
    what = "symmetry_planes and boundaries.rigid_walls";
  else if (!same_faces(now.fixed_faces, before.fixed_faces) || !same_faces(now.prescribed_faces, before.prescribed_faces))
    what = "boundaries.fixed_faces and boundaries.prescribed_faces";
  if (what)
    throw Error("--from " + from + ": the stage's " + what + " differ from the previous stage's; a stage keeps them "
                "(they hold the part's displacement from the start of the chain)");
}

// Nothing moves the part and no load acts on it: only its temperature can change (unless the scene
// asks its motion to go on: time.dwell off).
bool is_dwell(const Scene& scene) {
  return scene.time.dwell == "auto" && scene.dies.empty() && scene.prescribed_faces.empty() && norm(scene.loads.gravity) == 0;
}

}  // namespace

StageLink begin_stage(const std::string& from_arg, const std::string& case_dir, const Scene& scene, const Comm& comm,
                      std::string& checkpoint, DieCarry& carry) {
  const std::string from = std::filesystem::absolute(from_arg).lexically_normal().string();
  StageLink link;
  link.from = from;
  link.from_solve = solve_record_hash(from);
  if (!std::filesystem::is_directory(from)) throw Error("--from " + from + ": no such case folder");
  if (std::filesystem::equivalent(from, case_dir))
    throw Error("--from " + from + ": a stage starts from another case (to go on in this one, use --restart)");
  const Scene before = collectively(comm, [&] {
    if (!std::filesystem::exists(from + "/solve.json"))
      throw Error("--from " + from + ": the previous stage has not finished (no solve.json); run it to its end first");
    return load_scene(from + "/scene.resolved.yaml", {}, Side::solve);
  });
  StageLink previous;  // the previous case's own link, when it is a stage itself: its dies' starts
  collectively(comm, [&] {
    // a stage runs on its previous stage's ranks (its particles where they were): the previous rank files'
    // own message would have the user prepare the previous stage again
    const auto prepared_ranks = [](const std::string& dir) {  // prep.json's rank count, 0 where unreadable
      std::ifstream in(dir + "/prep.json");
      const auto j = nlohmann::json::parse(in, nullptr, false);
      return j.is_object() && j.contains("ranks") && j["ranks"].is_number_integer() ? j["ranks"].get<int>() : 0;
    };
    if (const int ranks = prepared_ranks(from); ranks > 0 && ranks != comm.size()) {
      const std::string n = std::to_string(ranks);
      const bool ready = prepared_ranks(case_dir) == ranks;  // only the job's count is off
      throw Error("--from " + from + ": the previous stage was prepared for " + n + " ranks and this job has " +
                  std::to_string(comm.size()) + "; a stage runs on its previous stage's ranks: " +
                  (ready ? "" : "prepare " + case_dir + " with rkprep --ranks " + n + " and ") + "run it with mpirun -np " + n);
    }
    if (!read_stage_link(from, previous)) previous.die_start.assign(before.dies.size(), 0.0);
    if (previous.die_start.size() != before.dies.size()) throw Error(from + "/stage.json: its dies are not its scene's");
    check_boundaries(scene, before, from);
    // the same part: the same particles at the same places on the same ranks
    const Subdomain s = read_subdomain(subdomain_path(from, comm.rank()), comm.rank(), comm.size(), "");
    const Subdomain mine = read_subdomain(subdomain_path(case_dir, comm.rank()), comm.rank(), comm.size(), "");
    if (s.global_id != mine.global_id || s.X != mine.X)
      throw Error("--from " + from + ": rank " + std::to_string(comm.rank()) + "'s particles are not this case's; "
                  "prepare the stage from the previous stage's geometry, spacing and rank count");
    carry.previous_triangles.clear();
    for (const DieSurface& d : s.dies) carry.previous_triangles.push_back(d.triangle_count());
    return 0;
  });
  checkpoint = restart_checkpoint(from, comm);
  link.start = collectively(comm, [&] { return H5File(checkpoint, H5File::Mode::read).read<double>("clock/scalars").at(0); });
  for (const Die& d : scene.dies) {
    int k = -1;
    for (std::size_t j = 0; j < before.dies.size(); ++j)
      if (before.dies[j].name == d.name) k = int(j);
    double start = link.start;
    if (k >= 0) {  // a die of the previous stage goes on as it was
      const Die& b = before.dies[std::size_t(k)];
      if (b.cad != d.cad || b.unit != d.unit || !same_motion(b.motion, d.motion))
        throw Error("--from " + from + ": die '" + d.name + "' is the previous stage's die by its name but its cad, unit or "
                    "motion differ; name it otherwise to start it from its CAD position, or keep them");
      if (d.motion.driven())
        throw Error("--from " + from + ": die '" + d.name + "' is driven by its press and cannot continue into another "
                    "stage; name it otherwise to start a new press motion from its CAD position");
      start = previous.die_start[std::size_t(k)];
      if (d.motion.cranked() && link.start + scene.time.end - start > d.motion.crank.bottom_dead_centre() * (1 + 1e-12))
        throw Error("--from " + from + ": die '" + d.name + "' goes on past its crank's bottom dead centre; end the stage there");
    }
    link.continues.push_back(k);
    link.die_start.push_back(start);
  }
  link.dwell = is_dwell(scene);
  carry.continues = link.continues;
  return link;
}

void apply_stage(const StageLink& link, Scene& scene) {
  scene.time.end += link.start;
  scene.time.start = link.start;
  for (std::size_t k = 0; k < scene.dies.size(); ++k) scene.dies[k].motion.start = link.die_start[k];
}

}  // namespace rk
