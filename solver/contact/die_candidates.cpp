#include "contact/die_candidates.hpp"

#include <algorithm>
#include <limits>

namespace rk {

DieCandidates::DieCandidates(std::size_t slaves, std::size_t dies)
    : slaves_(slaves), slot_(slaves * dies, -1), triangles_(kMost), boxes_(6 * kMost) {}

// Into the scratch, then into the list's room (grown where it is short): the list, then its near part.
// count: the scratch's, gathered at the search's skin, where the caller has it (-2: not yet)
void DieCandidates::gather(const DieSearch& search, const double y[3], List& list, int count) {
  for (int i = 0; i < 3; ++i) list.origin[i] = y[i];
  double skin = search.skin();
  for (int tries = 0; tries < 3 && count < 0; ++tries, skin = count < 0 ? skin / 4 : skin)
    if (tries > 0 || count < -1) count = search.candidates(y, skin, triangles_.data(), boxes_.data(), kMost);
  list.skin = float(skin * (1 - 1e-6));  // (less a millionth: the gathering's round-off)
  list.near_reach = float(kNear * skin);
  list.count = count;
  const double reach2 = double(list.near_reach) * double(list.near_reach);
  bool near[kMost];
  int near_count = 0;
  for (int k = 0; k < count; ++k) near_count += near[k] = box_distance2(&boxes_[6 * std::size_t(k)], y) <= reach2;
  list.near_count = near_count;
  if (count + near_count > list.capacity) {
    list.capacity = std::max(count + near_count, 2 * list.capacity);
    list.offset = triangles_.size();
    triangles_.resize(triangles_.size() + std::size_t(list.capacity));
    boxes_.resize(boxes_.size() + 6 * std::size_t(list.capacity));
  }
  auto keep = [&](int k, std::size_t to) {
    triangles_[to] = triangles_[std::size_t(k)];
    std::copy_n(&boxes_[6 * std::size_t(k)], 6, &boxes_[6 * to]);
  };
  for (int k = 0, at = count; k < count; ++k) {  // (the near part ascending, as the list)
    keep(k, list.offset + std::size_t(k));
    if (near[k]) keep(k, list.offset + std::size_t(at++));
  }
}

DieHit DieCandidates::nearest(const DieSearch& search, std::size_t die, std::size_t slave, const double y[3]) {
  if (!(search.skin() > 0)) return search.nearest(y);
  std::int32_t& slot = slot_[die * slaves_ + slave];
  if (slot < 0) {  // a list only for a slave that comes near the die (a far one is skipped by its clearance)
    const int count = search.candidates(y, search.skin(), triangles_.data(), boxes_.data(), kMost);
    if (count == 0) return DieHit{};
    slot = std::int32_t(lists_.size());
    lists_.push_back(List{{0, 0, 0}, 0, 0, 0, 0, -1, 0, 0});
    gather(search, y, lists_.back(), count);
  }
  List& list = lists_[std::size_t(slot)];
  double d2 = 0;  // within the skin of the origin the list holds every triangle within the margin of y
  for (int i = 0; i < 3; ++i) d2 += (y[i] - list.origin[i]) * (y[i] - list.origin[i]);
  if (!(d2 <= double(list.skin) * double(list.skin))) gather(search, y, list), d2 = 0;
  // every triangle past the near part lies, by its box, farther than this from y: more than the reach
  // less how far y moved (1-Lipschitz), less a billionth each for the round-off of both
  const double beyond = (double(list.near_reach) - std::sqrt(d2) * (1 + 1e-9)) * (1 - 1e-9);
  const std::size_t near = list.offset + std::size_t(std::max(list.count, 0));
  const DieHit hit = list.count < 0 ? search.nearest(y, list.last)
                                    : search.nearest_among(y, &triangles_[list.offset], &boxes_[6 * list.offset],
                                                           list.count, list.last, &triangles_[near], &boxes_[6 * near],
                                                           list.near_count, beyond > 0 ? beyond * beyond : 0.0);
  list.last = hit.triangle;
  return hit;
}

}  // namespace rk
