#include "history_columns.hpp"

namespace rk {
namespace {

constexpr const char* kWallColumns[] = {".force"};
constexpr const char* kDieColumns[] = {".stroke", ".force", ".fx", ".fy", ".fz", ".work", ".filled"};
constexpr const char* kRamColumns[] = {".speed", ".delivered"};  // a die driven by its press
constexpr const char* kFixedFaceColumns[] = {".fx", ".fy", ".fz"};
constexpr const char* kPrescribedFaceColumns[] = {".stroke", ".fx", ".fy", ".fz"};

}  // namespace

std::vector<std::string> history_columns(const Scene& scene) {
  std::vector<std::string> c;
  for (const auto& s : kHistoryScalars) c.push_back(s.name);
  if (scene.material.thermal())
    for (const auto& t : kTemperatureColumns) c.push_back(t.name);
  if (scene.material.conducting())
    for (const auto& t : kConductionColumns) c.push_back(t.name);
  if (scene.damage.on())
    for (const auto& t : kDamageColumns) c.push_back(t.name);
  if (scene.part_contact())
    for (const auto& t : kPartContactColumns) c.push_back(t.name);
  for (const auto& w : scene.rigid_walls)
    for (const char* q : kWallColumns) c.push_back(w.name + q);
  for (const auto& d : scene.dies) {
    for (const char* q : kDieColumns) c.push_back(d.name + q);
    if (scene.material.conducting()) c.push_back(d.name + ".heat");
    if (d.motion.driven())
      for (const char* q : kRamColumns) c.push_back(d.name + q);
  }
  for (const auto& f : scene.fixed_faces)
    for (const char* q : kFixedFaceColumns) c.push_back(f.name + q);
  for (const auto& f : scene.prescribed_faces)
    for (const char* q : kPrescribedFaceColumns) c.push_back(f.name + q);
  return c;
}

std::string history_unit(const std::string& column) {
  for (const auto& s : kHistoryScalars)
    if (column == s.name) return s.unit;
  for (const auto& s : kTemperatureColumns)
    if (column == s.name) return s.unit;
  for (const auto& s : kConductionColumns)
    if (column == s.name) return s.unit;
  for (const auto& s : kDamageColumns)
    if (column == s.name) return s.unit;
  for (const auto& s : kPartContactColumns)
    if (column == s.name) return s.unit;
  auto ends = [&](const char* tail) { return column.ends_with(tail); };
  if (ends(".work") || ends(".heat") || ends(".delivered")) return "J";
  if (ends(".speed")) return "m/s";
  if (ends(".force") || ends(".fx") || ends(".fy") || ends(".fz")) return "N";
  if (ends(".stroke")) return "m";
  return "-";
}

}  // namespace rk
