// Wang et al. 2007, section 4.1: partition INTEGRATION CELLS (METIS on the cells' dual graph, weighted by their
// integration points); each rank's local particles are those in the supports of its points (and
// of its owned surface particles, for the essential BCs), each particle has one owner, and
// per-neighbour overlap maps list the shared particles (Fig. 3 of Wang et al. 2007).
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "cad_mesh.hpp"
#include "discretize.hpp"
#include "subdomain.hpp"

namespace rk {

// Rank of every cell. "metis-kway" or "metis-recursive"; one rank needs no partitioner.
std::vector<std::int32_t> partition_cells(const VolumeMesh& mesh, const Discretization& disc, int ranks,
                                          const std::string& method);

struct SubdomainRequest {
  const VolumeMesh& mesh;
  const Discretization& disc;
  const std::vector<std::int32_t>& cell_rank;
  int ranks;
  double dilation;
  std::string scene_hash;
  const std::vector<DieSurface>& dies;
};

std::vector<Subdomain> build_subdomains(const SubdomainRequest& request);

// Per-rank table and totals (imbalance, overlap fraction, communication volume) for prep.json.
nlohmann::json partition_report(const std::vector<Subdomain>& subs, std::size_t particles);

}  // namespace rk
