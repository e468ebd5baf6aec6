// A result frame, the contract between rksolve (the writer, solver/io/output.cpp) and rkpost (the
// reader): the particle fields one rank writes at one output time, for its OWNED particles.
// CASE/results/rank_NNNN/frame_FFFFF.h5, written whole or not at all. Root attributes: `format`
// (kResultFrameFormat, checked by the reader), `rank`, `ranks`, `scene_hash` (of the subdomains it
// was computed on: a reader merges only its own case's frames). Datasets under frames/FFFFF/:
// time (s), step, global_id, x (3 per particle: the material's current position X + u^h(X), m),
// then kFrameFields, kThermalFields where the material has a temperature and kDamageFields where
// the scene asks for damage; with dies, the kDie* datasets below.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

namespace rk {

inline constexpr std::int64_t kResultFrameFormat = 1;

struct FrameField {
  const char* name;
  int components;
  const char* unit;
};

// Per particle. Point quantities are positive-weight averages of the points around the particle
// (docs/outputs.md); the stress is Cauchy's, in the order xx yy zz xy yz zx.
inline constexpr FrameField kFrameFields[] = {{"displacement", 3, "m"},   {"velocity", 3, "m/s"},
                                              {"eq_plastic_strain", 1, "-"}, {"von_mises", 1, "Pa"},
                                              {"pressure", 1, "Pa"},      {"stress", 6, "Pa"}};

// Written only where the scene's material has a temperature (material.specific_heat): the
// temperature, the plastic strain rate of the last increment and the flow stress at the particle's
// strain, rate and temperature. (Frames of rksolve before 2026-12-02 hold only the first.)
inline constexpr FrameField kThermalFields[] = {
    {"temperature", 1, "K"}, {"plastic_strain_rate", 1, "1/s"}, {"flow_stress", 1, "Pa"}};

// Written only where the scene has a `damage` section: the criteria of solver/material/damage.hpp
// (0 for one the scene does not ask for).
inline constexpr FrameField kDamageFields[] = {
    {"damage_cockcroft_latham", 1, "-"}, {"damage_brozzo", 1, "-"}, {"damage_oyane", 1, "-"}};

// With dies, over all dies' triangles in order (die k's after die k-1's): every die's stroke along
// its direction (m); this rank's contact loads on each triangle, 4 fixed-point integers (the normal
// force, >= 0, and the tangential force on the die, x y z) that sum over the ranks exactly, times
// die_load_scale (N per unit, one value); 1 where this rank's material has touched the triangle so
// far, else 0 on the die's working surface (facing the part) and -1 off it: the ranks' maximum is the
// die fill.
inline constexpr const char* kDieStroke = "die_stroke";
inline constexpr const char* kDieLoad = "die_load";
inline constexpr const char* kDieLoadScale = "die_load_scale";
inline constexpr const char* kDieTouched = "die_touched";

// CASE/results/rank_NNNN
inline std::string result_frame_dir(const std::string& case_dir, int rank) {
  char name[32];
  std::snprintf(name, sizeof name, "/results/rank_%04d", rank);
  return case_dir + name;
}

// CASE/results/rank_NNNN/frame_FFFFF.h5
inline std::string result_frame_path(const std::string& case_dir, int rank, std::int64_t frame) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame_%05lld.h5", static_cast<long long>(frame));
  return result_frame_dir(case_dir, rank) + name;
}

// The frame number of a file name frame_FFFFF.h5 in a rank's folder; -1 for any other name (a
// .tmp file a write left behind is not a frame).
inline long long result_frame_number(const std::string& file_name) {
  long long k = -1;
  if (std::sscanf(file_name.c_str(), "frame_%lld.h5", &k) != 1 || file_name.ends_with(".tmp")) return -1;
  return k;
}

// frames/FFFFF/: the group of the frame's datasets
inline std::string result_frame_group(std::int64_t frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frames/%05lld/", static_cast<long long>(frame));
  return name;
}

}  // namespace rk
