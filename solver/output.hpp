// Output: per-rank result frames of the OWNED particles (CASE/results/rank_NNNN.h5), the history
// (CASE/history.csv, rank 0) and particle values of point quantities. Only called at output steps.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "comm.hpp"
#include "energy.hpp"
#include "model.hpp"
#include "overlap_exchange.hpp"
#include "state.hpp"

namespace rk {

// Frame layout: frames/NNNNN/{time, step, global_id, x, displacement, velocity, eq_plastic_strain,
// von_mises, pressure}; root attribute `frames` = number of complete frames.
class ResultWriter {
 public:
  ResultWriter(const std::string& case_dir, const Model& md);
  // Collective (the particle values of point quantities need the overlap exchange).
  void write_frame(const Model& md, const State& st, const std::vector<double>& velocity, const Comm& comm);
  int frames() const { return frames_; }

 private:
  std::string path_;
  int frames_ = 0;
  OverlapExchange exchange_;
  std::vector<int128> partial_;
};

class HistoryWriter {  // rank 0 only: one header row, then one row of numbers per call
 public:
  HistoryWriter(const std::string& path, const std::vector<std::string>& columns);
  ~HistoryWriter();
  void write(const std::vector<double>& values);

 private:
  std::FILE* file_ = nullptr;
};

}  // namespace rk
