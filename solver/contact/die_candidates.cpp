#include "contact/die_candidates.hpp"

namespace rk {

DieCandidates::DieCandidates(std::size_t slaves, std::size_t dies) : slaves_(slaves), slot_(slaves * dies, -1), lists_(1) {}

void DieCandidates::gather(const DieSearch& search, const double y[3], List& list) const {
  for (int i = 0; i < 3; ++i) list.origin[i] = y[i];
  double skin = search.skin();
  for (int tries = 0; tries < 3; ++tries, skin /= 4)
    if ((list.count = search.candidates(y, skin, list.triangles, list.boxes, kCapacity)) >= 0) break;
  list.skin = float(skin * (1 - 1e-6));  // (less a millionth: the gathering's round-off)
}

DieHit DieCandidates::nearest(const DieSearch& search, std::size_t die, std::size_t slave, const double y[3]) {
  if (!(search.skin() > 0)) return search.nearest(y);
  std::int32_t& slot = slot_[die * slaves_ + slave];
  if (slot < 0) {  // a list only for a slave that comes near the die (a far one is skipped by its clearance)
    List& scratch = lists_[0];
    gather(search, y, scratch);
    if (scratch.count == 0) return DieHit{};
    scratch.last = -1;
    slot = std::int32_t(lists_.size());
    lists_.push_back(scratch);
  }
  List& list = lists_[std::size_t(slot)];
  double d2 = 0;  // within the skin of the origin the list holds every triangle within the margin of y
  for (int i = 0; i < 3; ++i) d2 += (y[i] - list.origin[i]) * (y[i] - list.origin[i]);
  if (!(d2 <= double(list.skin) * double(list.skin))) gather(search, y, list);
  const DieHit hit = list.count < 0 ? search.nearest(y, list.last)
                                    : search.nearest_among(y, list.triangles, list.boxes, list.count, list.last);
  list.last = hit.triangle;
  return hit;
}

}  // namespace rk
