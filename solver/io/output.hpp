// Output: per-rank result frames of the OWNED particles, with particle values of point quantities.
// Only called at output steps.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "energy.hpp"
#include "contact/die_fill.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "parallel/overlap_exchange.hpp"
#include "state.hpp"

namespace rk {

// Cauchy von Mises stress and pressure of a point from its Kirchhoff stress (sigma = tau / J).
void cauchy_measures(const double* tau, double J, double& von_mises, double& pressure);

// With conduction (the particles carry the field T^h), T^h at owned particle I's material, X_I + u^h(X_I):
// sum_J N_J(X_I) T_J (through the enthalpy with a specific heat table); the frames and the tracks add the
// points' pending plastic heat. 0 without conduction (the points' own temperatures are the field then).
double particle_field_temperature(const Model& md, const State& st, std::size_t I);
// The temperature a point adds to a particle's value: its temperature; with conduction only its plastic
// heating since the last thermal update (the particle's T^h above carries the rest).
double point_heat(const State& st, std::size_t g);

// The frame's files and layout: shared/result_frame.hpp.
class ResultWriter {
 public:
  // One file per frame, each written whole or not at all (io/durable_file.hpp). resume_frames < 0: a
  // new run (old frames are removed); otherwise keep the first resume_frames frames (a restart drops
  // the frames written after its checkpoint). Each frame carries the scene hash of the subdomains it
  // was computed on (rkpost merges only its own case's frames).
  ResultWriter(const std::string& case_dir, const Model& md, const std::string& scene_hash, std::int64_t resume_frames = -1);
  // Collective (the particle values of point quantities need the overlap exchange). `dies`: the
  // dies' strokes, loads and touched triangles (empty without dies).
  void write_frame(const Model& md, const State& st, const std::vector<double>& velocity, const Comm& comm,
                   const DieFrame& dies);
  int frames() const { return frames_; }

 private:
  std::string case_dir_, scene_hash_;
  int frames_ = 0;
  // point quantities spread to the particles, and the columns of the thermal and damage ones (-1: none)
  int thermal_col_, damage_col_, projected_;
  OverlapExchange exchange_;
  std::vector<Fixed> partial_;
  int headroom_ = -1;  // of the projection sums (force_headroom), set at the first frame
};


}  // namespace rk
