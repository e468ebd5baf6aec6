#include "report.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "error.hpp"

namespace rk {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

}  // namespace

void write_report(const std::string& case_dir) {
  namespace fs = std::filesystem;
  std::ifstream prep_file(case_dir + "/prep.json"), solve_file(case_dir + "/solve.json"), hist(case_dir + "/history.csv");
  if (!solve_file) throw Error(case_dir + "/solve.json: not found (run rksolve first)");
  const auto prep = nlohmann::json::parse(prep_file);
  const auto solve = nlohmann::json::parse(solve_file);
  std::string header, line, last;
  std::getline(hist, header);
  while (std::getline(hist, line))
    if (!line.empty()) last = line;
  const auto names = split(header), values = split(last);

  std::ofstream r(case_dir + "/report.md");
  r << "# rkforge run report\n\n";
  r << "| | |\n|---|---|\n";
  r << "| scene | `" << prep.value("scene", "?") << "` |\n";
  r << "| particles / cells / integration points | " << prep["particles"] << " / " << prep["cells"] << " / "
    << prep["integration_points"] << " |\n";
  r << "| ranks | " << solve["ranks"] << " (imbalance " << prep["partition"]["imbalance"] << ") |\n";
  r << "| simulated time | " << solve["time"] << " s in " << solve["steps"] << " steps |\n";
  r << "| wall time | " << solve["wall_s"] << " s (setup " << solve["setup_s"] << " s, prep " << prep["wall_s"]
    << " s) |\n";
  r << "| cost | " << solve["ns_per_point_update"] << " ns per integration-point update |\n";
  // the run's largest energy error decides the verdict (an error that peaked and fell back is not good)
  const double err = solve.value("max_energy_error", solve["energy_error"].get<double>());
  r << "| energy balance | largest error " << 100 * err << " % of the energy scale (at the end "
    << 100 * solve["energy_error"].get<double>() << " %): "
    << (err <= 0.01 ? "**good** (<= 1 %)" : err <= 0.05 ? "**acceptable** (<= 5 %)" : "**poor** (> 5 %)") << " |\n";
  if (solve.contains("max_pressure_ratio"))
    r << "| largest pressure | " << solve["max_pressure_ratio"] << " x (rho0 c_L v_max + sigma_y), rho0 c_L v_max = "
      << solve.value("impact_pressure_pa", 0.0) / 1e9 << " GPa (the run stops past health.max_pressure_ratio) |\n";
  if (solve.value("mass_scaling", 1.0) > 1)
    r << "| quasi-static | mass scaling " << solve["mass_scaling"] << ", max kinetic/internal "
      << 100 * solve.value("max_kinetic_internal_ratio", 0.0) << " % |\n";
  r << "\n## Wall time per phase (max over ranks)\n\n| phase | s |\n|---|---|\n";
  for (const auto& [name, t] : solve["phases"].items()) r << "| " << name << " | " << t["max_s"] << " |\n";
  r << "\n## Final values (history.csv)\n\n| quantity | value |\n|---|---|\n";
  for (std::size_t k = 0; k < names.size() && k < values.size(); ++k) r << "| " << names[k] << " | " << values[k] << " |\n";
  std::ifstream results_file(case_dir + "/plots/results.json");  // written by the scene's scripts
  if (results_file) {
    const auto results = nlohmann::json::parse(results_file, nullptr, false);
    if (results.is_array()) {
      r << "\n## Key results against the references\n\n| quantity | value | reference | difference | source |\n"
        << "|---|---|---|---|---|\n";
      for (const auto& q : results) {
        const double v = q.value("value", 0.0);
        r << "| " << q.value("quantity", "?") << " | " << v << " " << q.value("unit", "") << " | ";
        if (q.contains("reference") && q["reference"].is_number()) {
          const double ref = q["reference"].get<double>();
          r << ref << " | " << (ref != 0 ? 100 * (v / ref - 1) : 0.0) << " % | ";
        } else {
          r << "- | - | ";
        }
        r << q.value("source", "") << " |\n";
      }
    }
  }
  r << "\n## Files\n\n- ParaView: `vtk/case.pvd` (the part, its integration cells with their rank, and the dies over "
       "time)\n";
  if (fs::exists(case_dir + "/plots"))
    for (const auto& e : fs::directory_iterator(case_dir + "/plots"))
      if (e.path().extension() == ".png")
        r << "- ![" << e.path().stem().string() << "](plots/" << e.path().filename().string() << ")\n";
  if (!r.flush()) throw Error(case_dir + "/report.md: cannot write");
}

}  // namespace rk
