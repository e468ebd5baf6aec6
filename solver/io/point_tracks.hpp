// CASE/tracks.csv: the history of chosen material points (output.track), one row per history row:
// time, then per track NAME its current position NAME.x, .y, .z (the material's, X + u^h(X)) and its
// NAME.eq_plastic_strain, .von_mises, .pressure, with a temperature .temperature, with damage
// .damage_cockcroft_latham, .damage_brozzo and .damage_oyane: the values of the particle nearest the track's point
// at t = 0 (the lowest global id among equals), its point quantities averaged over the points whose
// supports hold it as the frames average them (docs/outputs.md). A track more than a spacing from
// every particle is refused by name. Rank 0 writes; a restart keeps the rows before it.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/history.hpp"
#include "model.hpp"
#include "parallel/comm.hpp"
#include "scene.hpp"
#include "state.hpp"

namespace rk {

class PointTracks {
 public:
  // Collective; throws rk::Error naming a track outside the part.
  PointTracks(const std::string& case_dir, const Scene& scene, const Model& md, double resume_time, const Comm& comm);
  // One row at t^n. Collective.
  void record(const Model& md, const State& st, const Comm& comm);

 private:
  struct Owned {
    std::size_t particle;
    int track;
  };
  struct Term {  // a point whose support holds a tracked particle
    std::size_t point, neighbour;  // neighbour: the index into md.nbr and md.N
    int track;
  };
  struct Mapping {  // what the lists were built on: a reference update renumbers the local particles
    std::int64_t updates = -1;
    std::size_t points = 0, neighbours = 0;
    bool operator==(const Mapping&) const = default;
  };
  std::vector<double> ids_;        // per track: the global id of its particle
  std::vector<Owned> owned_;       // the tracked particles this rank owns
  std::vector<Term> terms_;        // in the order of the points and their neighbours
  Mapping mapped_;
  int values_ = 0;                 // per track: x, y, z, eq_plastic_strain, von_mises, pressure [, T] [, 2 damage]
  std::vector<double> sums_, row_;
  std::unique_ptr<HistoryWriter> writer_;
  void map_locals(const Model& md, std::int64_t updates);
};

}  // namespace rk
