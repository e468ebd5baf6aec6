// A slave's candidate triangles of each die (a Verlet list): the triangles that can come within the
// die search's margin while the slave, in the die's frame, stays within the search's skin of where
// they were gathered. A slave in contact slides a spacing in hundreds of steps, so most of its
// lookups read a handful of triangles, their boxes in the same stream, instead of a bin's dozens (each
// a miss in memory), and start from the last lookup's triangle. A slave in contact reads only the
// list's near part, the triangles within kNear skins of the origin: any other lies farther from it, by
// its box, than its last hit. The hit is bit for bit the bin's (DieSearch::nearest_among), so the lists
// are not state: a restart starts without them.
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
  std::size_t slaves() const { return slaves_; }

 private:
  // At most this many triangles a list: where more lie within the skin (a die meshed far finer than
  // the particles), the skin shrinks 4x, twice, then the slave reads its bin.
  static constexpr int kMost = 256;
  // The near part's reach, in skins: a slave up to a skin from the origin still reads only it while its
  // last hit is within half a skin (a slave in contact: within its spring's depth).
  static constexpr double kNear = 1.5;
  struct List {
    double origin[3];        // where they were gathered (die frame)
    float skin;              // how far the slave may move from there (m)
    float near_reach;        // the near part: the list's triangles whose boxes lie within this of the origin (m)
    std::int32_t count;      // -1: more than kMost at the smallest skin
    std::int32_t near_count;  // the near part's, after the list's count in its room
    std::int32_t last;       // the last lookup's nearest triangle (-1: none): the search's hint
    std::int32_t capacity;   // its room in the pool
    std::size_t offset;      // its first triangle in the pool
  };
  void gather(const DieSearch& search, const double y[3], List& list, int count = -2);

  std::size_t slaves_ = 0;
  std::vector<std::int32_t> slot_;  // per die and slave: its list in lists_ (-1: none yet)
  std::vector<List> lists_;         // grows as slaves first come near a die
  // the lists' triangles and their boxes (lo[3], hi[3] rounded outward to float); a list that
  // outgrows its room moves to the end with twice the room (so the pool is at most about twice
  // what the lists hold); [0, kMost): the gathering's scratch
  std::vector<std::int32_t> triangles_;
  std::vector<float> boxes_;
};

}  // namespace rk
