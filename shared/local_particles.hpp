// Which particles a rank holds (Wang et al. 2007, Sec. 4.1, Fig. 3), shared by rkprep (the reference
// configuration) and rksolve's reference updates (the current one): the nodes of its integration
// cells, every particle whose support covers one of its integration points, and the whole support
// of every particle it owns (u^h(X_I): the essential-BC rows, the output, the reference updates'
// new positions). Particles are numbered by global id, so every rank count finds the same sets.
#pragma once
#include <cstdint>
#include <vector>

#include "neighbour_grid.hpp"

namespace rk {

struct LocalParticleRequest {
  const NeighbourGrid& grid;       // over all particles, radius = support
  const double* X;                 // 3 per particle: the positions the grid was built on
  std::vector<std::int32_t> cell_nodes;      // the rank's cells' nodes (global ids)
  std::vector<double> points;                // 3 per integration point of the rank
  std::vector<std::int32_t> owned;           // the particles the rank owns (global ids)
  // optional: groups of nearby points (an integration cell's), offsets into `points` from 0, each
  // searched once (NeighbourGrid::near_group); the points past the last group one search each
  std::vector<std::int32_t> point_groups;
};

// Ascending global ids.
std::vector<std::int32_t> local_particles(const LocalParticleRequest& request);

// Overlap maps of rank q from every rank's local set (ascending global ids each): per neighbour
// rank (ascending), the particles both hold, ascending global id, as indices into local[q].
void overlap_maps(const std::vector<std::vector<std::int32_t>>& local, int q, std::vector<std::int32_t>& neighbour_ranks,
                  std::vector<std::vector<std::int32_t>>& maps);

}  // namespace rk
