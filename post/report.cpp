#include "report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "error.hpp"
#include "folds.hpp"
#include "history_columns.hpp"
#include "phase_names.hpp"
#include "run_summary.hpp"
#include "text_file.hpp"

namespace rk {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

// A number as a person reads it: 4 significant digits (7.999999999999997e-05 -> 8e-05).
std::string num(double x, int digits = 4) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*g", digits, x);
  return b;
}

std::string num(const nlohmann::json& j, int digits = 4) { return j.is_number() ? num(j.get<double>(), digits) : "-"; }
}  // namespace

nlohmann::json read_prep_json(const std::string& case_dir) {
  const std::string path = case_dir + "/prep.json";
  std::ifstream in(path);
  if (!in) throw Error(path + ": not found (is this a case directory written by rkprep?)");
  try {
    nlohmann::json prep = nlohmann::json::parse(in);
    if (!prep.contains("ranks") || !prep["ranks"].is_number_integer() || prep["ranks"].get<int>() < 1)
      throw Error(path + ": holds no rank count ('ranks'); re-run rkprep on the case");
    return prep;
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not rkprep's JSON (" + e.what() + "); re-run rkprep on the case");
  }
}

void write_report(const std::string& case_dir, const std::vector<std::string>& fill_lines,
                  const std::vector<std::string>* folds, const std::vector<std::string>& skipped) {
  namespace fs = std::filesystem;
  std::ifstream hist(case_dir + "/history.csv");
  if (!hist) throw Error(case_dir + "/history.csv: cannot be read (rksolve writes it: run rksolve on the case first)");
  const nlohmann::json prep = read_prep_json(case_dir);
  // no solve.json: the run stopped on an error (a health check, a signal) or is still going
  const bool finished = fs::exists(case_dir + "/solve.json");
  const RunSummary solve = finished ? read_run_summary(case_dir + "/solve.json") : RunSummary{};
  std::string header, line, last;
  std::getline(hist, header);
  const auto names = split(header);
  // the columns' names are the history's format (shared/history_columns.hpp): the scalars lead
  for (std::size_t k = 0; k < std::size(kHistoryScalars); ++k)
    if (k >= names.size() || names[k] != kHistoryScalars[k].name)
      throw Error(case_dir + "/history.csv: written by another version of rksolve (column " + std::to_string(k + 1) +
                  " is '" + (k < names.size() ? names[k] : std::string()) + "', this rkpost reads '" +
                  kHistoryScalars[k].name + "'); re-run rksolve on the case");
  // each moving die (a `.stroke` and a `.force` column): its stroke and press force at every row
  struct Press {
    std::string die;
    std::size_t stroke = 0;  // the column
    std::vector<double> strokes, forces;
  };
  std::vector<Press> presses;
  for (std::size_t k = 0; k + 1 < names.size(); ++k)
    if (names[k].ends_with(".stroke") && names[k + 1] == names[k].substr(0, names[k].size() - 7) + ".force")
      presses.push_back({names[k].substr(0, names[k].size() - 7), k, {}, {}});
  for (std::size_t line_no = 2; std::getline(hist, line); ++line_no) {
    if (line.empty()) continue;
    const auto row = split(line);
    // a cell that is not a number: the file was cut or edited (one error naming the line and the column)
    const auto number = [&](std::size_t k) {
      char* end = nullptr;
      const double x = std::strtod(row[k].c_str(), &end);
      if (row[k].empty() || *end != '\0')
        throw Error(case_dir + "/history.csv:" + std::to_string(line_no) + ": column '" + names[k] + "' holds '" + row[k] +
                    "', not a number (a cut or edited file?); re-run rksolve on the case");
      return x;
    };
    try {
      for (std::size_t k = 0; k < row.size() && k < names.size(); ++k) number(k);  // (the last row's cells are read below)
    } catch (const Error& e) {
      if (hist.peek() != std::char_traits<char>::eof()) throw;
      std::fprintf(stderr, "rkpost: warning: %s; the row is left out (cut at the end: a full disk, or a run still going)\n", e.what());
      break;
    }
    last = line;
    for (auto& p : presses) {
      if (p.stroke + 1 >= row.size()) continue;
      p.strokes.push_back(number(p.stroke)), p.forces.push_back(number(p.stroke + 1));
    }
  }
  const auto values = split(last);

  std::ostringstream r;
  r << "# rkforge run report\n\n";
  r << "| | |\n|---|---|\n";
  r << "| scene | `" << prep.value("scene", "?") << "` |\n";
  r << "| particles / cells / integration points | " << prep["particles"] << " / " << prep["cells"] << " / "
    << prep["integration_points"] << " |\n";
  r << "| ranks | " << prep["ranks"] << " (imbalance " << num(prep["partition"]["imbalance"], 3) << ") |\n";
  for (const auto& w : solve.warnings) r << "| **warning** | " << w << " |\n";
  for (const auto& p : solve.presses) r << "| press | " << p << " |\n";
  for (const auto& f : skipped) r << "| **frame skipped by rkpost** | " << f << " |\n";
  if (!finished) {
    r << "| run | **not finished**: no solve.json (rksolve stopped with an error, its message says why, or is "
         "still running); history.csv ends at t = "
      << (values.empty() ? "-" : num(std::stod(values[0]))) << " s |\n";
  } else {
    r << "| simulated time | " << num(solve.time) << " s in " << solve.steps << " steps |\n";
    r << "| wall time | " << num(solve.wall_s, 3) << " s (setup " << num(solve.setup_s, 3) << " s, prep "
      << num(prep["wall_s"], 3) << " s) |\n";
    r << "| cost | " << num(solve.ns_per_point_update, 3) << " ns per integration-point update, "
      << num(solve.ns_per_particle_step, 3) << " ns per particle step |\n";
    if (solve.point_update_share < 1)
      r << "| multi-rate steps | " << num(100 * solve.point_update_share, 3)
        << " % of the point updates of one rate (time.subcycling) |\n";
    // the run's largest energy error decides the verdict (an error that peaked and fell back is not good)
    const double err = solve.max_energy_error;
    r << "| energy balance | largest error " << num(100 * err, 3) << " % of the energy scale past the start-up (the "
      << "first 100 steps and, for a part at rest at the start, 10 % of time.end; at the end "
      << num(100 * solve.energy_error, 3) << " %): "
      << (err <= 0.01 ? "**good** (<= 1 %)" : err <= 0.05 ? "**acceptable** (<= 5 %)" : "**poor** (> 5 %)") << " |\n";
    r << "| largest pressure | " << num(solve.max_pressure_ratio, 3) << " x (rho0 c_L v_max + sigma_y), "
      << "rho0 c_L v_max = " << num(solve.impact_pressure_pa / 1e9, 3)
      << " GPa (the run stops past health.max_pressure_ratio) |\n";
    if (solve.mass_scaling > 1)
      r << "| quasi-static | mass scaling " << num(solve.mass_scaling, 3) << ", max kinetic/internal "
        << num(100 * solve.max_kinetic_internal_ratio, 3) << " % past the first 5 % of time.end |\n";
    if (solve.thermal_updates > 0)
      r << "| heat transfer | " << solve.thermal_updates << " thermal updates, one per "
        << num(double(solve.steps) / double(solve.thermal_updates), 3) << " steps (the last stable thermal step "
        << num(solve.thermal_step_s, 3) << " s) |\n";
    r << "\n## Wall time per phase (max over ranks, in the step's order)\n\n| phase | s |\n|---|---|\n";
    for (const char* name : kPhaseNames)
      if (solve.phases.count(name)) r << "| " << name << " | " << num(solve.phases.at(name).max_s, 3) << " |\n";
  }
  r << "\n## " << (!finished ? "Last" : "Final") << " values (history.csv)\n\nThe modeled part's (a symmetry "
       "sector's, where the scene has symmetry planes), but for a die's press force `.force` and a ram's `.delivered`, "
       "which are the whole part's; a die's `.work` times its force_factor is the whole part's press work.\n\n"
       "| quantity | value | unit |\n|---|---|---|\n";
  for (std::size_t k = 0; k < names.size() && k < values.size(); ++k)
    r << "| " << names[k] << " | " << num(std::stod(values[k])) << " | " << history_unit(names[k]) << " |\n";
  std::ifstream results_file(case_dir + "/plots/results.json");  // written by the scene's scripts
  if (results_file) {
    const auto results = nlohmann::json::parse(results_file, nullptr, false);
    if (results.is_array()) {
      r << "\n## Key results against the references\n\n";
      // a run that did not finish: its last frame's values, which the references (of the whole run) do not measure
      // (a Taylor bar killed at 50 us read "+8.35 %" against the 80-us length)
      if (!finished)
        r << "The run did not finish: these are its last frame's values, not compared with the references, which are "
             "those of the whole run.\n\n";
      r << "| quantity | value | reference | difference | source |\n|---|---|---|---|---|\n";
      for (const auto& q : results) {
        const double v = q.value("value", 0.0);
        r << "| " << q.value("quantity", "?") << " | " << num(v) << " " << q.value("unit", "") << " | ";
        if (finished && q.contains("reference") && q["reference"].is_number()) {
          const double ref = q["reference"].get<double>();
          r << num(ref) << " | " << num(ref != 0 ? 100 * (v / ref - 1) : 0.0, 3) << " % | ";
        } else {
          r << "- | - | ";
        }
        r << q.value("source", "") << " |\n";
      }
    }
  }
  // the die fill: every die's filled fraction at the end (a `.filled` column; cases solved before
  // 2026-12-02 have none)
  std::vector<std::pair<std::string, double>> fill;
  for (std::size_t k = 0; k < names.size() && k < values.size(); ++k)
    if (names[k].ends_with(".filled")) fill.push_back({names[k].substr(0, names[k].size() - 7), std::stod(values[k])});
  if (!fill.empty()) {
    r << "\n## Die fill\n\nThe share of each die's surface that faces the part (within the modeled sector) which the material has touched "
         "(the dies' field `touched` in ParaView shows where; `contact_pressure` and `contact_shear` the loads).\n\n"
         "| die | filled |\n|---|---|\n";
    for (const auto& [die, f] : fill) r << "| " << die << " | " << num(100 * f, 3) << " % |\n";
    if (!fill_lines.empty()) r << "\nAt the last frame:\n\n";
    for (const auto& line : fill_lines) r << "- " << line << "\n";
  }
  if (folds) {
    r << "\n## Folds and laps\n\nWhere two parts of the free surface that were more than " << num(FoldFinder::kApart)
      << " spacings apart at t = 0 came within " << num(FoldFinder::kReach)
      << " spacing, facing each other (the particle field `fold` in ParaView shows them at every frame; with "
         "`contact.self` the part's contact with itself holds them about 0.75 spacing apart, without it they may "
         "pass through each other).\n\n";
    if (folds->empty()) r << "None found.\n";
    for (const auto& line : *folds) r << "- **" << line << "**\n";
  }
  std::erase_if(presses, [](const Press& p) {  // a die at rest is no press
    return std::all_of(p.strokes.begin(), p.strokes.end(), [](double s) { return s == 0; });
  });
  if (!presses.empty()) {
    // The force rings with the stress waves and jumps for a row or two at a reference update: the press is
    // sized by the peak of its running mean over 2 % of the rows (the force plot's), the largest single
    // row beside it (a row of such a transient read 33 % above the mean's peak on the hot upsetting)
    r << "\n## Press force\n\nThe whole part's, along the die's motion: the peak of the force's running mean over 2 % "
         "of the history rows (as in the force plot), and the largest single row (the force rings with the stress "
         "waves and jumps at a reference update).\n\n| die | peak of the running mean | at stroke | largest row | at "
         "stroke |\n|---|---|---|---|---|\n";
    for (const auto& p : presses) {
      const std::size_t n = p.forces.size(), k = std::max<std::size_t>(1, n / 50);
      double mean_peak = 0, mean_at = 0, sum = 0;
      std::size_t largest = 0;
      for (std::size_t i = 0; i < n; ++i) {  // the window [i + 1 - k, i], its mean at its middle row
        sum += p.forces[i] - (i >= k ? p.forces[i - k] : 0.0);
        if (i + 1 >= k && std::abs(sum / double(k)) > std::abs(mean_peak))
          mean_peak = sum / double(k), mean_at = p.strokes[i + 1 - k + k / 2];
        if (std::abs(p.forces[i]) > std::abs(p.forces[largest])) largest = i;
      }
      r << "| " << p.die << " | " << num(mean_peak / 1e3) << " kN | " << num(1e3 * mean_at) << " mm | "
        << num(p.forces[largest] / 1e3) << " kN | " << num(1e3 * p.strokes[largest]) << " mm |\n";
    }
    if (fs::exists(case_dir + "/plots/force_stroke.png")) r << "\n![force against stroke](plots/force_stroke.png)\n";
  }
  r << "\n## Files\n\n- ParaView: `vtk/case.pvd` (the part, its integration cells with their rank, and the dies over "
       "time)\n";
  std::vector<std::string> pictures;
  if (fs::exists(case_dir + "/plots"))
    for (const auto& e : fs::directory_iterator(case_dir + "/plots"))
      if (e.path().extension() == ".png") pictures.push_back(e.path().filename().string());
  std::sort(pictures.begin(), pictures.end());
  for (const auto& f : pictures) r << "- ![" << fs::path(f).stem().string() << "](plots/" << f << ")\n";
  write_text_file(case_dir + "/report.md", r.str());
}

}  // namespace rk
