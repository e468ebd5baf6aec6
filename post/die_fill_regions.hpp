// Where a die is not filled: the connected regions (triangles sharing a vertex) of its working surface
// that the material has not touched at a frame (the frame's `touched` = 0), largest first, each with
// its area and where it is, for report.md. On a closed die these are the corners and the thin
// sections the material did not reach at this spacing (or in this stroke).
#pragma once
#include <string>
#include <vector>

#include "subdomain.hpp"

namespace rk {

struct UnfilledRegion {
  double area = 0;            // m^2
  double centre[3] = {0, 0, 0};  // its area-weighted centre, m, at the die's position then
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  // its box
};

// touched: the die's triangles' values (1 touched, 0 working surface untouched, -1 off it); shift: the
// die's displacement at that frame (m).
std::vector<UnfilledRegion> unfilled_regions(const DieSurface& die, const std::vector<double>& touched, const double shift[3]);

// "die 'NAME': filled P % of its working surface; unfilled: A mm^2 around (x, y, z) mm (extent ...), ..."
std::string describe_fill(const std::string& name, const DieSurface& die, const std::vector<double>& touched,
                          const double shift[3], std::size_t most = 5);

}  // namespace rk
