#include "run_summary.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

#include "error.hpp"
#include "text_file.hpp"

namespace rk {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(PhaseTime, min_s, max_s)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(RunSummary, format, steps, time, wall_s, setup_s, ranks, particles,
                                                integration_points, neighbours_per_point, point_updates_per_s,
                                                ns_per_point_update, ns_per_particle_step, point_update_share, plastic_fraction, energy_error, max_energy_error,
                                                max_pressure_ratio, impact_pressure_pa, ebc_method, constraints,
                                                max_ebc_error_m, initial_kinetic_energy, viscous_work, mass_scaling, stable_step, step_ratio,
                                                max_kinetic_internal_ratio, reference_updates, frames, thermal_updates, thermal_step_s,
                                                peak_memory_mb_max_rank, peak_bytes_per_point, resident_bytes_per_point,
                                                phases, warnings, presses)

void write_run_summary(const std::string& path, const RunSummary& summary) {
  write_text_file(path, nlohmann::json(summary).dump(2) + "\n");
}

RunSummary read_run_summary(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot read");
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw Error(path + ": not a JSON object (a damaged file?)");
  const std::int64_t format = j.value("format", std::int64_t(0));
  if (format != kRunSummaryFormat)
    throw Error(path + ": written by another version of rksolve (format " + std::to_string(format) + ", this one reads " +
                std::to_string(kRunSummaryFormat) + "); re-run rksolve on the case");
  try {
    return j.get<RunSummary>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": " + e.what());
  }
}

}  // namespace rk
