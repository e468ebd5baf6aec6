// Wang et al. 2007, Sec. 4.2 (Figs. 3-4): each rank computes partial sums for its local particles from its
// own integration points; the partials of the particles shared with each neighbour rank are
// exchanged with non-blocking MPI and added. The partials are 64-bit fixed point
// (parallel/fixed_point.hpp), so every copy of a shared particle gets the bitwise same total.
#pragma once
#include <mpi.h>

#include <vector>

#include "model.hpp"
#include "parallel/fixed_point.hpp"

namespace rk {

class OverlapExchange {
 public:
  OverlapExchange(const Model& model, int width);  // width = values per particle
  // Posts the receives, packs and sends this rank's partials of the shared particles.
  void start(const std::vector<Fixed>& partial);
  // Waits and adds the neighbours' partials into `partial`.
  void finish(std::vector<Fixed>& partial);
  void sum(std::vector<Fixed>& partial) {
    start(partial);
    finish(partial);
  }

 private:
  const Model& model_;
  int width_;
  std::vector<std::vector<Fixed>> send_, recv_;
  std::vector<MPI_Request> requests_;
};

}  // namespace rk
