// CASE/history.csv, the contract between rksolve (the writer) and rkpost and the scripts (readers):
// a header row of column names, then one row of numbers (%.10g) per history time, SI units, for the
// modeled part. The columns are named: readers find a column by its name, never by its position.
// First the run's scalars (kHistoryScalars), then where the material has a temperature its
// mass-weighted mean, minimum and maximum over the part's points (kTemperatureColumns), with
// conduction the heat given to the ambient (kConductionColumns), with damage its criteria's largest
// values (kDamageColumns), then per rigid wall its force along
// its normal, per die its stroke, press force (along its motion, times force_factor: the whole part's),
// force components, press work (the modeled part's, like the energies), filled fraction (the touched share of its surface that faces the part) and
// with conduction the heat conducted into it, for a press-driven die its ram's speed and delivered energy,
// per fixed face its reaction components, per prescribed face its stroke and reaction components.
#pragma once
#include <string>
#include <vector>

#include "scene.hpp"

namespace rk {

struct HistoryColumn {
  const char* name;
  const char* unit;  // "s", "J", "N", "m", "count" or "-" (a fraction)
};

inline constexpr HistoryColumn kHistoryScalars[] = {
    {"time", "s"},            {"dt", "s"},                  {"kinetic", "J"},
    {"internal", "J"},        {"plastic_work", "J"},        {"external_work", "J"},
    {"contact_work", "J"},    {"energy_error", "-"},        {"friction_work", "J"},
    {"contacts", "count"},    {"point_contacts", "count"},  {"max_penetration", "m"},
    {"kinetic_internal_ratio", "-"}, {"volume_change", "-"}, {"ebc_error", "m"},
    {"update_work", "J"},     {"spring_energy", "J"},       {"symmetry_depth", "m"},
    {"viscous_work", "J"}};

inline constexpr HistoryColumn kTemperatureColumns[] = {
    {"temperature_mean", "K"}, {"temperature_min", "K"}, {"temperature_max", "K"}};

// With heat conduction (material.conductivity): the heat the part gave the ambient air by convection
// and radiation, cumulative; and per die (its column DIE.heat) the heat conducted into it.
inline constexpr HistoryColumn kConductionColumns[] = {{"heat_to_ambient", "J"}};

// With the part's contact with itself or between bodies (Scene::part_contact): the surface particles in
// contact with another part of the part this step (each pair counted at both its particles).
inline constexpr HistoryColumn kPartContactColumns[] = {{"part_contacts", "count"}};

// With a `damage` section: each criterion's largest value over the part's points.
inline constexpr HistoryColumn kDamageColumns[] = {
    {"damage_cockcroft_latham_max", "-"}, {"damage_brozzo_max", "-"}, {"damage_oyane_max", "-"}};

// The scene's columns in order: the scalars, then its walls', dies' and faces' columns.
std::vector<std::string> history_columns(const Scene& scene);

// The unit of a column of any scene ("-" for a fraction or an unknown name).
std::string history_unit(const std::string& column);

}  // namespace rk
