// Flow lines (Scene::Output::FlowLines): the particles are material points, so the ones that lay on a
// plane at t = 0, taken as lines along a direction in it, drawn through their current positions at
// every frame show how the material flowed: the deformed part's "grain flow" of a billet cut from bar
// stock. A particle joins the line k (in-plane offset k x spacing across the direction) when it lies
// within half a particle spacing of the plane and of that offset and is the nearest to the line of
// those in its layer (within a quarter spacing along it); a line's particles are joined in the order
// of their position along the direction at t = 0.
#pragma once
#include <cstdint>
#include <vector>

#include "scene.hpp"
#include "vtu_writer.hpp"

namespace rk {

struct FlowLineSet {
  std::vector<std::int64_t> particles;  // indices into the particles (by global id), line after line
  std::vector<std::int64_t> line;       // per entry of `particles`: its line's number (0, 1, ...)
  VtuCells lines;  // each line as segments (VTK_LINE: ParaView and meshio read them) over those points
};

// X: the particles' positions at t = 0, 3 each, in global-id order; h: the particle spacing.
FlowLineSet select_flow_lines(const Scene::Output::FlowLines& spec, const std::vector<double>& X, double h);

}  // namespace rk
