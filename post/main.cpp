// rkpost: merge the ranks' result frames into one .vtu per frame and a .pvd time series (or, with
// --partitioned, one .vtu piece per rank and a .pvtu per frame, for ParaView to read in parallel).
//   rkpost CASE [--frames 0,4,-1] [--fields eq_plastic_strain,stress] [--uncompressed] [--partitioned]
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "case_layout.hpp"
#include "case_lock.hpp"
#include "chain.hpp"
#include "cli.hpp"
#include "die_fill_regions.hpp"
#include "flow_lines.hpp"
#include "folds.hpp"
#include "h5file.hpp"
#include "pictures.hpp"
#include "pvtu_writer.hpp"
#include "report.hpp"
#include "run_summary.hpp"
#include "result_frame.hpp"
#include "scene.hpp"
#include "subdomain.hpp"
#include "vtu_writer.hpp"

namespace fs = std::filesystem;

namespace {

// The particle fields of a result frame (shared/result_frame.hpp), written as ParaView point data.
using Field = rk::FrameField;
constexpr const auto& kFields = rk::kFrameFields;

struct Frame {
  double time = 0;
  // with dies (frames before 2026-12-02 hold none): each die's stroke, and over all dies' triangles the
  // loads summed over the ranks (normal force, tangential force x y z, N) and whether any rank's
  // material has touched it
  std::vector<double> die_stroke, die_load, die_touched;
  std::vector<std::int64_t> gid, rank;
  std::vector<double> x;
  std::vector<std::vector<double>> values;  // per selected field
};

// A frame of another case (another scene's subdomains) or of another format: never merged, never
// skipped quietly.
struct ForeignFrame : rk::Error {
  using rk::Error::Error;
};

// The path of rank r's result frame f, which must be there (else an error naming it).
std::string result_frame_file(const std::string& case_dir, int r, int f) {
  const std::string path = rk::result_frame_path(case_dir, r, f);
  if (!fs::exists(path)) throw rk::Error(path + ": missing (the rank did not write this frame)");
  return path;
}

// A result frame must be of this rkpost's format and computed on this case's subdomains (else a ForeignFrame).
void check_result_frame(const rk::H5File& h, const std::string& scene_hash) {
  const std::string& path = h.path();
  const std::int64_t format = h.has_attr("format") ? h.attr_int("format") : 0;
  if (format != rk::kResultFrameFormat)
    throw ForeignFrame(path + ": written by another version of rksolve (frame format " + std::to_string(format) +
                       ", this rkpost reads " + std::to_string(rk::kResultFrameFormat) + "); re-run rksolve on the case");
  const std::string hash = h.has_attr("scene_hash") ? h.attr_string("scene_hash") : "none";
  if (hash != scene_hash)
    throw ForeignFrame(path + ": computed on another scene's subdomains (scene hash " + hash + ", this case's " +
                       scene_hash + "): a result of an earlier case; re-run rksolve on this case");
}

// The particles of rank r's frame (group g of h) appended to fr; with `only` (ascending global ids),
// just those of them. Returns how many were appended.
std::size_t append_particles(const rk::H5File& h, const std::string& g, int r, const std::vector<Field>& fields,
                             Frame& fr, const std::vector<std::int64_t>* only = nullptr) {
  const auto gid = h.read<std::int64_t>(g + "global_id");
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k < gid.size(); ++k)
    if (!only || std::binary_search(only->begin(), only->end(), gid[k])) rows.push_back(k);
  const auto append = [&](const auto& from, std::size_t width, auto& to) {
    if (rows.size() == gid.size()) {
      to.insert(to.end(), from.begin(), from.end());
      return;
    }
    for (std::size_t k : rows) to.insert(to.end(), from.begin() + std::ptrdiff_t(width * k), from.begin() + std::ptrdiff_t(width * (k + 1)));
  };
  fr.rank.insert(fr.rank.end(), rows.size(), std::int64_t(r));
  append(gid, 1, fr.gid);
  append(h.read<double>(g + "x", 3), 3, fr.x);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const auto width = std::size_t(fields[k].components);
    append(h.read<double>(g + fields[k].name, width), width, fr.values[k]);
  }
  return rows.size();
}

// particles: false for the frame's time and dies alone
Frame read_frame(const std::string& case_dir, int ranks, int f, const std::vector<Field>& fields,
                 const std::string& scene_hash, bool particles = true) {
  Frame fr;
  fr.values.resize(fields.size());
  const std::string g = rk::result_frame_group(f);
  std::vector<std::int64_t> die_sum;
  double scale = 0;
  for (int r = 0; r < ranks; ++r) {
    const std::string path = result_frame_file(case_dir, r, f);
    const rk::H5File h(path, rk::H5File::Mode::read);
    check_result_frame(h, scene_hash);
    fr.time = h.read<double>(g + "time")[0];
    if (h.exists(g + rk::kDieStroke)) {  // the dies: the loads' fixed-point sums are exact over the ranks
      fr.die_stroke = h.read<double>(g + rk::kDieStroke);
      const auto load = h.read<std::int64_t>(g + rk::kDieLoad, 4);
      const auto touched = h.read<std::int64_t>(g + rk::kDieTouched);
      if (r == 0) die_sum.assign(load.size(), 0), fr.die_touched.assign(touched.size(), -1.0);
      if (load.size() != die_sum.size() || touched.size() != fr.die_touched.size())
        throw rk::Error(path + ": its die surfaces differ from rank 0's");
      for (std::size_t k = 0; k < load.size(); ++k) die_sum[k] += load[k];
      for (std::size_t k = 0; k < touched.size(); ++k) fr.die_touched[k] = std::max(fr.die_touched[k], double(touched[k]));
      scale = h.read<double>(g + rk::kDieLoadScale)[0];  // the same on every rank
    }
    if (particles) append_particles(h, g, r, fields, fr);
  }
  for (std::int64_t v : die_sum) fr.die_load.push_back(double(v) * scale);
  return fr;
}

// A die's cell data from a frame: the contact pressure and shear stress on each triangle (its loads
// over its area, Pa) and whether the material has touched it so far (the die fill); none where the
// frame holds no die datasets.
std::vector<rk::VtuArray> die_fields(const rk::DieSurface& die, const Frame& fr, std::size_t first) {
  const std::size_t n = die.triangle_count();
  if (fr.die_touched.size() < first + n) return {};
  rk::VtuArray pressure{"contact_pressure", 1, {}, {}}, shear{"contact_shear", 1, {}, {}}, touched{"touched", 1, {}, {}};
  for (std::size_t t = 0; t < n; ++t) {
    double normal[3];
    const double area = die.area_normal(t, normal);
    const double* f = &fr.die_load[4 * (first + t)];
    pressure.f64.push_back(area > 0 ? f[0] / area : 0.0);
    shear.f64.push_back(area > 0 ? std::sqrt(f[1] * f[1] + f[2] * f[2] + f[3] * f[3]) / area : 0.0);
    touched.f64.push_back(fr.die_touched[first + t]);
  }
  return {pressure, shear, touched};
}

// Particle I of a prepared subdomain at t = 0 appended to fr (as its owner's): at rest but for the
// scene's initial velocity, every other field 0.
void append_prepared(const rk::Subdomain& sub, std::size_t I, const std::vector<Field>& fields, const rk::Scene& scene,
                     Frame& fr) {
  fr.gid.push_back(sub.global_id[I]);
  fr.rank.push_back(sub.owner[I]);
  const double* X = &sub.X[3 * I];
  fr.x.insert(fr.x.end(), X, X + 3);
  for (std::size_t k = 0; k < fields.size(); ++k)
    for (int c = 0; c < fields[k].components; ++c) {
      double v = 0;
      if (std::string(fields[k].name) == "velocity") {
        const auto& G = scene.initial.velocity_gradient;
        v = scene.initial.velocity[c] + G[3 * c] * X[0] + G[3 * c + 1] * X[1] + G[3 * c + 2] * X[2];
      }
      fr.values[k].push_back(v);
    }
}

// A case prepared but not solved: its particles at t = 0 from the subdomain files (each rank's owned
// ones).
Frame prepared_frame(const std::string& case_dir, int ranks, const std::vector<Field>& fields, const rk::Scene& scene) {
  Frame fr;
  fr.values.resize(fields.size());
  for (int r = 0; r < ranks; ++r) {
    const rk::Subdomain sub = rk::read_subdomain(rk::subdomain_path(case_dir, r), r, ranks, scene.prep_hash);
    for (std::size_t I = 0; I < sub.particle_count(); ++I)
      if (sub.owner[I] == r) append_prepared(sub, I, fields, scene, fr);
  }
  return fr;
}

// Reorders by global id and checks that every particle appears exactly once.
void sort_by_global_id(Frame& fr, const std::vector<Field>& fields, const std::string& where) {
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
  permute(fr.gid, 1), permute(fr.rank, 1), permute(fr.x, 3);
  for (std::size_t k = 0; k < fields.size(); ++k) permute(fr.values[k], fields[k].components);
}

// The integration cells of every rank (hexahedra or tetrahedra on the particles, by global id),
// with the rank that integrates each: the partition as Figs. 8c, 13 and 18 of Wang et al. 2007 show it.
std::pair<rk::VtuCells, std::vector<std::int64_t>> read_cells(const std::string& case_dir, int ranks,
                                                              const std::string& prep_hash) {
  rk::VtuCells cells;
  std::vector<std::int64_t> owner;
  for (int r = 0; r < ranks; ++r) {
    const rk::Subdomain s = rk::read_subdomain(rk::subdomain_path(case_dir, r), r, ranks, prep_hash);
    std::int64_t nodes[8];
    for (std::size_t c = 0; c < s.cell_count(); ++c) {
      const int count = s.cell_node_offsets[c + 1] - s.cell_node_offsets[c];
      for (int k = 0; k < count; ++k) nodes[k] = s.global_id[s.cell_nodes[s.cell_node_offsets[c] + k]];
      cells.add(nodes, count, count == 8 ? rk::kVtkHexahedron : rk::kVtkTetra);
      owner.push_back(r);
    }
  }
  return {cells, owner};
}

// With bodies (Scene::bodies): each particle's body by global id (0: the part), from the ranks' owned
// particles' flags; empty without bodies.
std::vector<std::int64_t> read_bodies(const std::string& case_dir, int ranks, const rk::Scene& scene, std::int64_t particles) {
  std::vector<std::int64_t> body;
  if (scene.bodies.empty()) return body;
  body.assign(std::size_t(particles), 0);
  for (int r = 0; r < ranks; ++r) {
    const rk::Subdomain s = rk::read_subdomain(rk::subdomain_path(case_dir, r), r, ranks, scene.prep_hash);
    for (std::size_t I = 0; I < s.particle_count(); ++I)
      if (s.owner[I] == r && s.global_id[I] >= 0 && s.global_id[I] < particles) body[std::size_t(s.global_id[I])] = rk::body_of(s.flags[I]);
  }
  return body;
}

// The point array `body` of the particles `gid` (none without bodies).
void add_bodies(const std::vector<std::int64_t>& body, const std::vector<std::int64_t>& gid, std::vector<rk::VtuArray>& data) {
  if (body.empty()) return;
  std::vector<std::int64_t> of(gid.size());
  for (std::size_t k = 0; k < gid.size(); ++k) of[k] = body[std::size_t(gid[k])];
  data.push_back({"body", 1, {}, std::move(of)});
}

// --partitioned: frame f as one .vtu piece per rank, CASE/vtk/frame_FFFFF/rank_RRRR.vtu, and
// CASE/vtk/frame_FFFFF.pvtu listing them, for ParaView to read in parallel. A piece holds the rank's
// owned particles, its own integration cells and the points of those cells that other ranks own,
// with the owners' values, marked vtkGhostType = 1 (VTK's DUPLICATEPOINT: a copy of a point another
// piece owns) so that ParaView counts every particle once; every other array is the merged file's.
// The ranks one at a time: rkpost holds one rank's subdomain, frame and piece (and, while it copies
// the ghosts' values, one neighbouring rank's frame), not every rank's; each frame file is read once
// for its own piece and once for each piece that needs points of it. particles: how many the case has; fold: the whole part's fold flags by global id
// (empty: none written).
void write_pieces(const std::string& case_dir, int f, int ranks, std::int64_t particles, bool solved,
                  const std::vector<Field>& fields, const rk::Scene& scene, const std::vector<std::int64_t>& fold,
                  const std::vector<std::int64_t>& body, bool compress) {
  char stem[32];
  std::snprintf(stem, sizeof stem, "frame_%05d", f);
  fs::create_directories(case_dir + "/vtk/" + stem);
  const std::string g = rk::result_frame_group(f);
  std::vector<std::string> sources;
  std::vector<rk::PvtuArray> point_schema, cell_schema;
  std::vector<bool> seen(std::size_t(particles), false);  // every particle owned by one piece
  std::int64_t owned_total = 0;
  for (int r = 0; r < ranks; ++r) {
    const rk::Subdomain sub = rk::read_subdomain(rk::subdomain_path(case_dir, r), r, ranks, scene.prep_hash);
    // the points of the rank's cells that other ranks own, by owner, in ascending global id (the subdomain's order)
    std::vector<char> ghost(sub.particle_count(), 0);
    for (std::int32_t I : sub.cell_nodes) ghost[std::size_t(I)] = sub.owner[std::size_t(I)] != r;
    std::map<int, std::vector<std::int64_t>> ghosts;
    for (std::size_t I = 0; I < sub.particle_count(); ++I)
      if (ghost[I]) ghosts[sub.owner[I]].push_back(sub.global_id[I]);
    Frame piece;
    piece.values.resize(fields.size());
    if (solved) {
      {
        const rk::H5File h(result_frame_file(case_dir, r, f), rk::H5File::Mode::read);
        check_result_frame(h, scene.prep_hash);
        append_particles(h, g, r, fields, piece);
      }
      for (const auto& [s, ids] : ghosts) {
        const rk::H5File h(result_frame_file(case_dir, s, f), rk::H5File::Mode::read);
        check_result_frame(h, scene.prep_hash);
        const std::size_t found = append_particles(h, g, s, fields, piece, &ids);
        if (found != ids.size())
          throw rk::Error(h.path() + ": holds " + std::to_string(found) + " of the " + std::to_string(ids.size()) +
                          " particles that rank " + std::to_string(r) + "'s cells need from it");
      }
    } else {  // prepared, not solved: every point from the rank's own subdomain
      for (std::size_t I = 0; I < sub.particle_count(); ++I)
        if (sub.owner[I] == r) append_prepared(sub, I, fields, scene, piece);
      for (std::size_t I = 0; I < sub.particle_count(); ++I)
        if (ghost[I]) append_prepared(sub, I, fields, scene, piece);
    }
    const std::size_t n = piece.gid.size();
    std::unordered_map<std::int64_t, std::int64_t> point_of(n);  // global id -> the piece's point
    std::vector<std::uint8_t> ghost_type(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
      const std::int64_t id = piece.gid[k];
      point_of.emplace(id, std::int64_t(k));
      if (piece.rank[k] != r) {
        ghost_type[k] = 1;
      } else if (id < 0 || id >= particles || seen[std::size_t(id)]) {
        throw rk::Error(case_dir + " frame " + std::to_string(f) + ": particles are missing or duplicated across ranks (global id " +
                        std::to_string(id) + " on rank " + std::to_string(r) + ")");
      } else {
        seen[std::size_t(id)] = true, ++owned_total;
      }
    }
    rk::VtuCells cells;
    std::int64_t nodes[8];
    for (std::size_t c = 0; c < sub.cell_count(); ++c) {
      const int count = sub.cell_node_offsets[c + 1] - sub.cell_node_offsets[c];
      for (int k = 0; k < count; ++k) {
        const auto I = std::size_t(sub.cell_nodes[std::size_t(sub.cell_node_offsets[c] + k)]);
        const auto at = point_of.find(sub.global_id[I]);
        if (at == point_of.end())
          throw rk::Error(rk::result_frame_path(case_dir, r, f) + ": holds no particle " + std::to_string(sub.global_id[I]) +
                          ", a node of the rank's cells");
        nodes[k] = at->second;
      }
      cells.add(nodes, count, count == 8 ? rk::kVtkHexahedron : rk::kVtkTetra);
    }
    std::vector<rk::VtuArray> data;
    data.push_back({"global_id", 1, {}, piece.gid});
    for (std::size_t k = 0; k < fields.size(); ++k) data.push_back({fields[k].name, fields[k].components, std::move(piece.values[k]), {}});
    data.push_back({"rank", 1, {}, std::move(piece.rank)});
    add_bodies(body, piece.gid, data);
    if (!fold.empty()) {
      std::vector<std::int64_t> on(n);
      for (std::size_t k = 0; k < n; ++k) on[k] = fold[std::size_t(piece.gid[k])];
      data.push_back({"fold", 1, {}, std::move(on)});
    }
    data.push_back({"vtkGhostType", 1, {}, {}, std::move(ghost_type)});
    const std::vector<rk::VtuArray> cell_data = {{"rank", 1, {}, std::vector<std::int64_t>(sub.cell_count(), r)}};
    char piece_name[64];
    std::snprintf(piece_name, sizeof piece_name, "%s/rank_%04d.vtu", stem, r);
    rk::write_vtu(case_dir + "/vtk/" + piece_name, piece.x, data, cells, cell_data, compress);
    sources.push_back(piece_name);
    if (r == 0) point_schema = rk::pvtu_arrays(data), cell_schema = rk::pvtu_arrays(cell_data);
  }
  if (owned_total != particles)
    throw rk::Error(case_dir + " frame " + std::to_string(f) + ": the ranks own " + std::to_string(owned_total) + " of the " +
                    std::to_string(particles) + " particles");
  rk::write_pvtu(case_dir + "/vtk/" + stem + ".pvtu", point_schema, cell_schema, sources);
}

// --fields: a comma-separated subset of kFields ("all": every one).
// thermal: how many of kThermalFields the frames hold (0 without a temperature; 1, the temperature
// alone, in frames of rksolve before 2026-12-02); damage: how many of kDamageFields they hold (0
// without damage; 2, without Oyane's, in frames of rksolve before 2026-12-02)
std::vector<Field> select_fields(const std::string& list, int thermal, int damage) {
  std::vector<Field> known(std::begin(kFields), std::end(kFields));
  known.insert(known.end(), std::begin(rk::kThermalFields), std::begin(rk::kThermalFields) + thermal);
  known.insert(known.end(), std::begin(rk::kDamageFields), std::begin(rk::kDamageFields) + damage);
  if (list == "all") return known;
  std::vector<Field> out;
  std::stringstream ss(list);
  for (std::string name; std::getline(ss, name, ',');) {
    auto it = std::find_if(known.begin(), known.end(), [&](const Field& f) { return name == f.name; });
    if (it == known.end()) {
      std::string names;
      for (const auto& f : known) names += std::string(names.empty() ? "" : ", ") + f.name;
      throw rk::Error("--fields: '" + name + "' is not a field of this case (known: " + names + ")");
    }
    out.push_back(*it);
  }
  return out;
}

// --frames: "all", or comma-separated frame numbers, negative ones counted from the end (-1: last).
std::vector<int> select_frames(const std::string& list, int frames) {
  std::vector<int> out;
  if (list == "all") {
    for (int f = 0; f < frames; ++f) out.push_back(f);
    return out;
  }
  std::stringstream ss(list);
  for (std::string item; std::getline(ss, item, ',');) {
    char* end = nullptr;
    const long k = std::strtol(item.c_str(), &end, 10);
    const long f = k < 0 ? frames + k : k;
    if (item.empty() || *end != '\0' || f < 0 || f >= frames)
      throw rk::Error("--frames: '" + item + "' is not a frame of this case (0 to " + std::to_string(frames - 1) +
                      ", or -1 for the last)");
    if (std::find(out.begin(), out.end(), int(f)) == out.end()) out.push_back(int(f));
  }
  if (out.empty()) throw rk::Error("--frames: '" + list + "' names no frame (all, or a list like 0,4,-1)");
  std::sort(out.begin(), out.end());
  return out;
}

int run(int argc, char** argv) {
  CLI::App app{"rkpost: merge the ranks' results into VTK files for ParaView (CASE/vtk/case.pvd)", "rkpost"};
  rk::add_version_flag(app);
  std::string case_dir;
  std::string frame_list = "all", field_list = "all";
  bool quiet = false, uncompressed = false;
  app.add_option("case", case_dir, "case directory (after rksolve)")->required();
  app.add_option("--frames", frame_list, "frames to write: all, or a list like 0,4,-1 (-1: the last)");
  app.add_option("--fields", field_list,
                 "point fields to write: all, or a list of displacement, velocity, eq_plastic_strain, von_mises, "
                 "pressure, stress (global_id and rank are always written)");
  app.add_flag("--uncompressed", uncompressed, "write the VTK arrays without zlib compression");
  bool partitioned = false;
  app.add_flag("--partitioned", partitioned,
               "write each frame as one piece per rank (vtk/frame_FFFFF/rank_RRRR.vtu: its owned particles, its cells and "
               "their points owned elsewhere as vtkGhostType ghosts) and a .pvtu listing them, for ParaView to read in "
               "parallel (pvbatch, pvserver); rkpost builds one rank's piece at a time instead of the whole part's frame");
  bool no_pictures = false, plots_only = false;
  auto* none = app.add_flag("--no-pictures", no_pictures, "skip the plots and ParaView pictures (CASE/plots/)");
  app.add_flag("--plots-only", plots_only,
               "the energy and force plots without the ParaView pictures (a second a case instead of several)")
      ->excludes(none);
  app.add_flag("--quiet", quiet, "print nothing but errors");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  const nlohmann::json prep = rk::read_prep_json(case_dir);
  const int ranks = prep["ranks"].get<int>();
  std::int64_t frames = 0;  // the highest frame any rank wrote, plus one
  // no results at all: a case prepared and not solved yet, shown as it starts (frame 0 from the subdomains)
  const bool solved = fs::exists(case_dir + "/results");
  for (int r = 0; r < ranks && solved; ++r) {
    const std::string dir = rk::result_frame_dir(case_dir, r);
    if (!fs::is_directory(dir)) throw rk::Error(dir + ": not found (has rksolve run on this case?)");
    for (const auto& entry : fs::directory_iterator(dir))
      frames = std::max<std::int64_t>(frames, rk::result_frame_number(entry.path().filename().string()) + 1);
  }
  // frames missing at the end on every rank (deleted, a disk that filled) would pass unseen: the run's own count
  if (solved && fs::exists(case_dir + "/solve.json")) {
    if (const std::int64_t written = rk::read_run_summary(case_dir + "/solve.json").frames; written > frames)
      std::fprintf(stderr, "rkpost: warning: %s/solve.json says the run wrote %lld frames, but results/ holds %lld: the "
                   "last ones are missing on every rank\n", case_dir.c_str(), static_cast<long long>(written),
                   static_cast<long long>(frames));
  }
  fs::create_directories(case_dir + "/vtk");
  // an earlier, longer run's files past this run's last frame would pass for its results: removed
  // (frame_FFFFF.vtu, die_NAME_FFFFF.vtu, and of --partitioned, frame_FFFFF.pvtu and its pieces' folder frame_FFFFF)
  for (const auto& entry : fs::directory_iterator(case_dir + "/vtk")) {
    const std::string file = entry.path().filename().string();
    const std::string stem = file.ends_with(".pvtu") ? file.substr(0, file.size() - 5)
                             : file.ends_with(".vtu") ? file.substr(0, file.size() - 4)
                             : entry.is_directory()   ? file
                                                      : std::string();
    const auto digits = stem.size() >= 5 ? stem.substr(stem.size() - 5) : std::string();
    const bool numbered = digits.size() == 5 && digits.find_first_not_of("0123456789") == std::string::npos &&
                          (stem.starts_with("frame_") || (file.ends_with(".vtu") && stem.starts_with("die_")));
    if (numbered && std::stoll(digits) >= std::max<std::int64_t>(frames, 1)) fs::remove_all(entry.path());
  }
  // the dies, placed at their stroke at each frame's time (a part of their own in the .pvd)
  const rk::Scene scene = rk::load_scene(case_dir + "/scene.resolved.yaml", {}, rk::Side::solve);
  std::vector<rk::DieSurface> dies;
  if (!scene.dies.empty())
    dies = rk::read_subdomain(rk::subdomain_path(case_dir, 0), 0, ranks, scene.prep_hash).dies;
  // which fields the frames hold, from rank 0's first frame that opens (a damaged one is skipped below)
  std::optional<rk::H5File> first;
  int first_frame = -1;
  for (int f = 0; solved && f < int(frames) && !first; ++f) {
    const std::string path = rk::result_frame_path(case_dir, 0, f);
    try {
      if (fs::exists(path)) first.emplace(path, rk::H5File::Mode::read), first_frame = f;
    } catch (const rk::Error&) {
    }
  }
  const auto holds = [&](const char* name) { return first && first->exists(rk::result_frame_group(first_frame) + name); };
  // the temperature where the material has one (and the run wrote it)
  int thermal = 0;
  if (solved && scene.material.thermal()) thermal = holds(rk::kThermalFields[1].name) || !first ? int(std::size(rk::kThermalFields)) : 1;
  // the damage fields where the frames hold them (a `damage` section, in the scene or set at rksolve)
  int damage = 0;
  while (damage < int(std::size(rk::kDamageFields)) && holds(rk::kDamageFields[damage].name)) ++damage;
  first.reset();
  const std::vector<Field> fields = select_fields(field_list, thermal, damage);
  const std::vector<int> chosen = select_frames(frame_list, solved ? int(frames) : 1);
  // the whole part's cells: in every merged frame; with --partitioned only to find the folds (each
  // piece reads its own rank's cells)
  const bool find_folds = solved && field_list == "all";
  auto [cells, cell_rank] = !partitioned || find_folds ? read_cells(case_dir, ranks, scene.prep_hash)
                                                       : std::pair<rk::VtuCells, std::vector<std::int64_t>>();
  std::vector<rk::PvdEntry> index;
  const std::vector<std::int64_t> body = read_bodies(case_dir, ranks, scene, prep["particles"].get<std::int64_t>());
  // the flow lines' particles, chosen on the positions at t = 0 (post/flow_lines.hpp)
  std::vector<rk::FlowLineSet> flow;
  std::optional<rk::FoldFinder> folding;  // the part's free surface, to find folds at each frame
  std::vector<rk::Fold> folds;
  if (!scene.output.flow_lines.empty() || find_folds) {
    Frame start = prepared_frame(case_dir, ranks, {}, scene);
    sort_by_global_id(start, {}, case_dir + " at t = 0");
    if (find_folds) folding.emplace(cells, start.x, scene.discretization.spacing, scene.symmetry_planes);
    for (const auto& spec : scene.output.flow_lines) {
      flow.push_back(rk::select_flow_lines(spec, start.x, scene.discretization.spacing));
      if (flow.back().particles.empty())
        std::fprintf(stderr, "rkpost: warning: output.flow_lines '%s': no particle within half a spacing of its plane\n",
                     spec.name.c_str());
    }
  }
  if (partitioned) cells = {}, cell_rank = {};  // the fold finder holds the surface it needs
  // the fields of the whole part's frame: merged, all of them; partitioned, the pieces hold them and the
  // whole part only the positions (for the folds and flow lines) and the plastic strain where flow lines show it
  const auto strain = std::find_if(fields.begin(), fields.end(), [](const Field& q) { return std::string(q.name) == "eq_plastic_strain"; });
  const std::vector<Field> whole_fields = !partitioned                             ? fields
                                          : strain != fields.end() && !flow.empty() ? std::vector<Field>{*strain}
                                                                                    : std::vector<Field>{};
  const bool whole_particles = !partitioned || folding || !flow.empty();
  const auto whole_strain = std::find_if(whole_fields.begin(), whole_fields.end(),
                                         [](const Field& q) { return std::string(q.name) == "eq_plastic_strain"; });
  int skipped = 0;
  std::vector<std::string> skipped_why;  // (for report.md)
  std::vector<std::string> fill;  // the dies' fill at the last frame written
  for (int f : chosen) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "frame_%05d", f);
    const std::string vtk = case_dir + "/vtk/";
    // the frame's pieces and .pvtu from an earlier rkpost are replaced, never mixed with this one's (and a
    // frame is one layout or the other: with --partitioned, the merged file is removed too)
    fs::remove(vtk + stem + ".pvtu"), fs::remove_all(vtk + stem);
    if (partitioned) fs::remove(vtk + stem + ".vtu");
    Frame fr;
    try {  // a frame missing on a rank or half written is reported and skipped; the rest is merged
      if (solved) fr = read_frame(case_dir, ranks, f, whole_fields, scene.prep_hash, whole_particles);
      else if (whole_particles) fr = prepared_frame(case_dir, ranks, whole_fields, scene);
      sort_by_global_id(fr, whole_fields, case_dir + " frame " + std::to_string(f));
      if (partitioned) {
        write_pieces(case_dir, f, ranks, prep["particles"].get<std::int64_t>(), solved, fields, scene,
                     folding ? folding->find(fr.x, fr.time, folds) : std::vector<std::int64_t>(), body, !uncompressed);
      }
    } catch (const ForeignFrame&) {
      if (partitioned) fs::remove_all(vtk + stem);
      throw;
    } catch (const rk::Error& e) {
      if (partitioned) fs::remove_all(vtk + stem);  // no piece of a frame without its .pvtu
      std::fprintf(stderr, "rkpost: frame %d skipped: %s\n", f, e.what());
      skipped_why.push_back("frame " + std::to_string(f) + ": " + e.what());
      ++skipped;
      continue;
    }
    const std::string name = stem + std::string(partitioned ? ".pvtu" : ".vtu");
    if (!partitioned) {
      std::vector<rk::VtuArray> data;
      data.push_back({"global_id", 1, {}, fr.gid});
      for (std::size_t k = 0; k < fields.size(); ++k) data.push_back({fields[k].name, fields[k].components, fr.values[k], {}});
      data.push_back({"rank", 1, {}, fr.rank});
      add_bodies(body, fr.gid, data);
      if (folding) data.push_back({"fold", 1, {}, folding->find(fr.x, fr.time, folds)});
      rk::write_vtu(vtk + name, fr.x, data, cells, {{"rank", 1, {}, cell_rank}}, !uncompressed);
    }
    index.push_back({fr.time, 0, name, "part"});
    std::size_t first_triangle = 0;  // die k's first in the frame's die datasets
    for (std::size_t k = 0; k < dies.size(); ++k) {
      const auto& die = scene.dies[k];
      std::vector<double> x = dies[k].vertices;
      const double stroke = k < fr.die_stroke.size() ? fr.die_stroke[k] : die.motion.stroke(fr.time);
      for (std::size_t v = 0; v < x.size(); ++v) x[v] += stroke * die.motion.direction[v % 3];
      char file[160];
      std::snprintf(file, sizeof file, "die_%s_%05d.vtu", die.name.c_str(), f);
      rk::write_vtu(case_dir + "/vtk/" + file, x, {}, rk::VtuCells::triangles(dies[k].triangles),
                    die_fields(dies[k], fr, first_triangle), !uncompressed);
      if (k == 0) fill.clear();
      if (fr.die_touched.size() >= first_triangle + dies[k].triangle_count()) {
        const std::vector<double> touched(fr.die_touched.begin() + std::ptrdiff_t(first_triangle),
                                          fr.die_touched.begin() + std::ptrdiff_t(first_triangle + dies[k].triangle_count()));
        const double shift[3] = {stroke * die.motion.direction[0], stroke * die.motion.direction[1], stroke * die.motion.direction[2]};
        fill.push_back(rk::describe_fill(die.name, dies[k], touched, shift));
      }
      first_triangle += dies[k].triangle_count();
      index.push_back({fr.time, int(k + 1), file, die.name});
    }
    for (std::size_t k = 0; k < flow.size(); ++k) {  // the flow lines through the particles' current positions
      const auto& spec = scene.output.flow_lines[k];
      std::vector<double> x;
      rk::VtuArray ep{"eq_plastic_strain", 1, {}, {}};
      for (std::int64_t I : flow[k].particles) {
        x.insert(x.end(), &fr.x[3 * std::size_t(I)], &fr.x[3 * std::size_t(I)] + 3);
        if (whole_strain != whole_fields.end()) ep.f64.push_back(fr.values[std::size_t(whole_strain - whole_fields.begin())][std::size_t(I)]);
      }
      std::vector<rk::VtuArray> data = {{"line", 1, {}, flow[k].line}};
      if (!ep.f64.empty()) data.push_back(ep);
      char file[160];
      std::snprintf(file, sizeof file, "flow_%s_%05d.vtu", spec.name.c_str(), f);
      rk::write_vtu(case_dir + "/vtk/" + file, x, data, flow[k].lines, {}, !uncompressed);
      index.push_back({fr.time, int(dies.size() + 1 + k), file, spec.name});
    }
  }
  if (solved && !chosen.empty() && skipped == int(chosen.size()))  // (each said above) nothing to show: an error
    throw rk::Error(case_dir + ": none of the " + std::to_string(chosen.size()) + " frames asked for could be merged "
                    "(each skipped, above); no case.pvd written");
  rk::write_pvd(case_dir + "/vtk/case.pvd", index);
  if (!solved) {  // nothing solved: the discretization only (report.md comes with a run)
    if (!quiet)
      std::printf("rkpost: %s is prepared, not solved: %s/vtk/case.pvd shows its particles, its cells by rank and "
                  "%zu dies at t = 0\n", case_dir.c_str(), case_dir.c_str(), dies.size());
    return 0;
  }
  if (!no_pictures) rk::make_pictures(case_dir, quiet, !plots_only);  // before the report, which lists them
  std::vector<std::string> fold_lines;
  for (const rk::Fold& f : folds) fold_lines.push_back(rk::describe_fold(f));
  rk::write_report(case_dir, fill, folding ? &fold_lines : nullptr, skipped_why);
  if (!fs::exists(case_dir + "/solve.json") && rk::case_locked(case_dir))  // a run still going: its frames so far
    std::fprintf(stderr, "rkpost: warning: %s: rksolve is still running in it (it holds %s/%s): these are its frames so far\n",
                 case_dir.c_str(), case_dir.c_str(), rk::kSolveLock);
  else if (!fs::exists(case_dir + "/solve.json"))  // a run a health check stopped: its frames are there to look at
    std::fprintf(stderr, "rkpost: warning: %s has no solve.json: the run did not finish (report.md says so)\n",
                 case_dir.c_str());
  if (!quiet)
    std::printf("rkpost: %lld frames of %d ranks %s into %s/vtk/case.pvd (%d skipped, %zu dies)\n",
                static_cast<long long>(chosen.size() - skipped), ranks,
                partitioned ? "written as one piece per rank (.pvtu)" : "merged", case_dir.c_str(), skipped, dies.size());
  if (const int stages = rk::write_chain_pvd(case_dir, index); stages > 0 && !quiet)
    std::printf("rkpost: the chain of %d stages, one sequence: %s/vtk/chain.pvd\n", stages, case_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return rk::guarded_main("rkpost", [&] { return run(argc, argv); }); }
