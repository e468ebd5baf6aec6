// A slave's candidate triangles of each die (a Verlet list): the triangles that can come within the
// die search's margin while the slave, in the die's frame, stays within a skin of where they were
// gathered. A slave in contact slides a spacing in hundreds of steps, so most of its lookups read a
// handful of triangles, their boxes in the same stream, instead of a bin's dozens (each a miss in
// memory), and start from the last lookup's triangle. The hit is bit for bit the bin's
// (DieSearch::nearest_among), so the lists are not state: a restart starts without them.
#pragma once
#include <cstdint>
#include <vector>

#include "die_search.hpp"

namespace rk {

class DieCandidates {
 public:
  DieCandidates() = default;
  DieCandidates(std::size_t slaves, std::size_t dies);
  // die's closest point to y (in the die's frame) for this slave: search.nearest(y)'s answer
  DieHit nearest(const DieSearch& search, std::size_t die, std::size_t slave, const double y[3]);

 private:
  // At most this many triangles a list: where more lie within the search's skin (a die's finely
  // meshed fillet), the skin shrinks 4x, twice, then the slave reads its bin.
  static constexpr int kCapacity = 48;
  struct List {
    double origin[3];  // where they were gathered (die frame)
    float skin;        // how far the slave may move from there (m)
    std::int32_t count;  // -1: more than kCapacity at the smallest skin
    std::int32_t last;   // the last lookup's nearest triangle (-1: none): the search's hint
    std::int32_t triangles[kCapacity];
    float boxes[6 * kCapacity];  // theirs
  };
  void gather(const DieSearch& search, const double y[3], List& list) const;

  std::size_t slaves_ = 0;
  std::vector<std::int32_t> slot_;  // per die and slave: its list in lists_ (-1: none yet)
  std::vector<List> lists_;         // [0] the gathering's scratch; grows as slaves first come near a die
};

}  // namespace rk
