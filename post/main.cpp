// rkpost: merge the ranks' result frames into one .vtu per frame and a .pvd time series.
//   rkpost CASE [--frames 0,4,-1] [--fields eq_plastic_strain,stress] [--uncompressed]
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>
#include <sstream>

#include "cli.hpp"
#include "die_fill_regions.hpp"
#include "flow_lines.hpp"
#include "folds.hpp"
#include "h5file.hpp"
#include "pictures.hpp"
#include "chain.hpp"
#include "report.hpp"
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

Frame read_frame(const std::string& case_dir, int ranks, int f, const std::vector<Field>& fields,
                 const std::string& scene_hash) {
  Frame fr;
  fr.values.resize(fields.size());
  const std::string g = rk::result_frame_group(f);
  std::vector<std::int64_t> die_sum;
  double scale = 0;
  for (int r = 0; r < ranks; ++r) {
    const std::string path = rk::result_frame_path(case_dir, r, f);
    if (!fs::exists(path)) throw rk::Error(path + ": missing (the rank did not write this frame)");
    const rk::H5File h(path, rk::H5File::Mode::read);
    const std::int64_t format = h.has_attr("format") ? h.attr_int("format") : 0;
    if (format != rk::kResultFrameFormat)
      throw ForeignFrame(path + ": written by another version of rksolve (frame format " + std::to_string(format) +
                         ", this rkpost reads " + std::to_string(rk::kResultFrameFormat) + "); re-run rksolve on the case");
    const std::string hash = h.has_attr("scene_hash") ? h.attr_string("scene_hash") : "none";
    if (hash != scene_hash)
      throw ForeignFrame(path + ": computed on another scene's subdomains (scene hash " + hash + ", this case's " +
                         scene_hash + "): a result of an earlier case; re-run rksolve on this case");
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
    auto gid = h.read<std::int64_t>(g + "global_id");
    fr.rank.insert(fr.rank.end(), gid.size(), std::int64_t(r));
    fr.gid.insert(fr.gid.end(), gid.begin(), gid.end());
    const auto x = h.read<double>(g + "x", 3);
    fr.x.insert(fr.x.end(), x.begin(), x.end());
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const auto v = h.read<double>(g + fields[k].name, std::size_t(fields[k].components));
      fr.values[k].insert(fr.values[k].end(), v.begin(), v.end());
    }
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

// A case prepared but not solved: its particles at t = 0 from the subdomain files (each rank's owned
// ones), at rest but for the scene's initial velocity, every other field 0.
Frame prepared_frame(const std::string& case_dir, int ranks, const std::vector<Field>& fields, const rk::Scene& scene) {
  Frame fr;
  fr.values.resize(fields.size());
  for (int r = 0; r < ranks; ++r) {
    const rk::Subdomain sub = rk::read_subdomain(rk::subdomain_path(case_dir, r), r, ranks, scene.prep_hash);
    for (std::size_t I = 0; I < sub.particle_count(); ++I) {
      if (sub.owner[I] != r) continue;
      fr.gid.push_back(sub.global_id[I]);
      fr.rank.push_back(r);
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
  bool no_pictures = false;
  app.add_flag("--no-pictures", no_pictures, "skip the plots and ParaView pictures (CASE/plots/)");
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
  // no results at all: a case prepared and not solved yet, shown as it starts (frame 0 from the subdomains)
  const bool solved = fs::exists(case_dir + "/results");
  for (int r = 0; r < ranks && solved; ++r) {
    const std::string dir = rk::result_frame_dir(case_dir, r);
    if (!fs::is_directory(dir)) throw rk::Error(dir + ": not found (has rksolve run on this case?)");
    for (const auto& entry : fs::directory_iterator(dir))
      frames = std::max<std::int64_t>(frames, rk::result_frame_number(entry.path().filename().string()) + 1);
  }
  fs::create_directories(case_dir + "/vtk");
  // an earlier, longer run's files past this run's last frame would pass for its results: removed
  for (const auto& entry : fs::directory_iterator(case_dir + "/vtk")) {
    const std::string file = entry.path().filename().string();
    const auto digits = file.size() >= 9 ? file.substr(file.size() - 9, 5) : std::string();
    const bool numbered = file.ends_with(".vtu") && digits.size() == 5 && digits.find_first_not_of("0123456789") == std::string::npos &&
                          (file.starts_with("frame_") || file.starts_with("die_"));
    if (numbered && std::stoll(digits) >= std::max<std::int64_t>(frames, 1)) fs::remove(entry.path());
  }
  // the dies, placed at their stroke at each frame's time (a part of their own in the .pvd)
  const rk::Scene scene = rk::load_scene(case_dir + "/scene.resolved.yaml", {}, rk::Side::solve);
  std::vector<rk::DieSurface> dies;
  if (!scene.dies.empty())
    dies = rk::read_subdomain(rk::subdomain_path(case_dir, 0), 0, ranks, scene.prep_hash).dies;
  // the temperature where the material has one (and the run wrote it)
  int thermal = 0;  // the thermal fields the frames hold, from rank 0's first frame
  if (solved && scene.material.thermal()) {
    thermal = int(std::size(rk::kThermalFields));
    const std::string first = rk::result_frame_path(case_dir, 0, 0);
    if (fs::exists(first) && !rk::H5File(first, rk::H5File::Mode::read).exists(rk::result_frame_group(0) + rk::kThermalFields[1].name))
      thermal = 1;
  }
  // the damage fields where the frames hold them (a `damage` section, in the scene or set at rksolve)
  int damage = 0;
  if (solved && fs::exists(rk::result_frame_path(case_dir, 0, 0))) {
    const rk::H5File first(rk::result_frame_path(case_dir, 0, 0), rk::H5File::Mode::read);
    while (damage < int(std::size(rk::kDamageFields)) && first.exists(rk::result_frame_group(0) + rk::kDamageFields[damage].name)) ++damage;
  }
  const std::vector<Field> fields = select_fields(field_list, thermal, damage);
  const std::vector<int> chosen = select_frames(frame_list, solved ? int(frames) : 1);
  const auto [cells, cell_rank] = read_cells(case_dir, ranks, scene.prep_hash);
  std::vector<rk::PvdEntry> index;
  // the flow lines' particles, chosen on the positions at t = 0 (post/flow_lines.hpp)
  std::vector<rk::FlowLineSet> flow;
  std::optional<rk::FoldFinder> folding;  // the part's free surface, to find folds at each frame
  std::vector<rk::Fold> folds;
  if (!scene.output.flow_lines.empty() || (solved && field_list == "all")) {
    Frame start = prepared_frame(case_dir, ranks, {}, scene);
    sort_by_global_id(start, {}, case_dir + " at t = 0");
    if (solved && field_list == "all") folding.emplace(cells, start.x, scene.discretization.spacing, scene.symmetry_planes);
    for (const auto& spec : scene.output.flow_lines) {
      flow.push_back(rk::select_flow_lines(spec, start.x, scene.discretization.spacing));
      if (flow.back().particles.empty())
        std::fprintf(stderr, "rkpost: warning: output.flow_lines '%s': no particle within half a spacing of its plane\n",
                     spec.name.c_str());
    }
  }
  const auto strain = std::find_if(fields.begin(), fields.end(), [](const Field& q) { return std::string(q.name) == "eq_plastic_strain"; });
  int skipped = 0;
  std::vector<std::string> fill;  // the dies' fill at the last frame written
  for (int f : chosen) {
    Frame fr;
    try {  // a frame missing on a rank or half written is reported and skipped; the rest is merged
      fr = solved ? read_frame(case_dir, ranks, f, fields, scene.prep_hash) : prepared_frame(case_dir, ranks, fields, scene);
      sort_by_global_id(fr, fields, case_dir + " frame " + std::to_string(f));
    } catch (const ForeignFrame&) {
      throw;
    } catch (const rk::Error& e) {
      std::fprintf(stderr, "rkpost: frame %d skipped: %s\n", f, e.what());
      ++skipped;
      continue;
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.vtu", f);
    std::vector<rk::VtuArray> data;
    data.push_back({"global_id", 1, {}, fr.gid});
    for (std::size_t k = 0; k < fields.size(); ++k) data.push_back({fields[k].name, fields[k].components, fr.values[k], {}});
    data.push_back({"rank", 1, {}, fr.rank});
    if (folding) data.push_back({"fold", 1, {}, folding->find(fr.x, fr.time, folds)});
    rk::write_vtu(case_dir + "/vtk/" + name, fr.x, data, cells, {{"rank", 1, {}, cell_rank}}, !uncompressed);
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
        if (strain != fields.end()) ep.f64.push_back(fr.values[std::size_t(strain - fields.begin())][std::size_t(I)]);
      }
      std::vector<rk::VtuArray> data = {{"line", 1, {}, flow[k].line}};
      if (!ep.f64.empty()) data.push_back(ep);
      char file[160];
      std::snprintf(file, sizeof file, "flow_%s_%05d.vtu", spec.name.c_str(), f);
      rk::write_vtu(case_dir + "/vtk/" + file, x, data, flow[k].lines, {}, !uncompressed);
      index.push_back({fr.time, int(dies.size() + 1 + k), file, spec.name});
    }
  }
  rk::write_pvd(case_dir + "/vtk/case.pvd", index);
  if (!solved) {  // nothing solved: the discretization only (report.md comes with a run)
    if (!quiet)
      std::printf("rkpost: %s is prepared, not solved: %s/vtk/case.pvd shows its particles, its cells by rank and "
                  "%zu dies at t = 0\n", case_dir.c_str(), case_dir.c_str(), dies.size());
    return 0;
  }
  if (!no_pictures) rk::make_pictures(case_dir, quiet);  // before the report, which lists them
  std::vector<std::string> fold_lines;
  for (const rk::Fold& f : folds) fold_lines.push_back(rk::describe_fold(f));
  rk::write_report(case_dir, fill, folding ? &fold_lines : nullptr);
  if (!fs::exists(case_dir + "/solve.json"))  // a run a health check stopped: its frames are there to look at
    std::fprintf(stderr, "rkpost: warning: %s has no solve.json: the run did not finish (report.md says so)\n",
                 case_dir.c_str());
  if (!quiet)
    std::printf("rkpost: %lld frames of %d ranks merged into %s/vtk/case.pvd (%d skipped, %zu dies)\n",
                static_cast<long long>(chosen.size() - skipped), ranks, case_dir.c_str(), skipped, dies.size());
  if (const int stages = rk::write_chain_pvd(case_dir, index); stages > 0 && !quiet)
    std::printf("rkpost: the chain of %d stages, one sequence: %s/vtk/chain.pvd\n", stages, case_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return rk::guarded_main("rkpost", [&] { return run(argc, argv); }); }
