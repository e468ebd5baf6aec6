// The pictures and plots of a solved case, made by rkpost when their tools are installed:
// CASE/plots/energies.png and force_stroke.png (every moving die's press force against its stroke;
// matplotlib, scripts/history_plots.py) and part_ep_FFFFF.png / part_rank_FFFFF.png at the first and
// last frames (the part by plastic strain with the dies, the cells by rank; ParaView off-screen,
// scripts/pictures.py). A tool that is missing or fails is a warning, never an error: the VTK files
// are the result. What the tools printed goes to CASE/plots/pictures.log. Without `renders`, the plots only.
#pragma once
#include <string>

namespace rk {

void make_pictures(const std::string& case_dir, bool quiet, bool renders);

}  // namespace rk
