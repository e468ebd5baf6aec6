#include "subcycles.hpp"

#include <algorithm>
#include <array>
#include <bit>

#include "state.hpp"

namespace rk {
namespace {

// entries sorted by their class (a counting sort, stable), and per level the end of those due
void sort_by_class(std::span<const std::int32_t> entries, const auto& class_of, int levels, std::vector<std::int32_t>& out,
                   std::vector<std::size_t>& end) {
  end.assign(std::size_t(Subcycles::kMaxLevels) + 1, 0);
  for (const std::int32_t e : entries) ++end[std::size_t(class_of(e))];
  for (std::size_t k = 1; k < end.size(); ++k) end[k] += end[k - 1];
  std::array<std::size_t, Subcycles::kMaxLevels + 1> next{};
  for (std::size_t k = 1; k < end.size(); ++k) next[k] = end[k - 1];
  out.resize(entries.size());
  for (const std::int32_t e : entries) out[next[std::size_t(class_of(e))]++] = e;
  for (auto k = std::size_t(levels) + 1; k < end.size(); ++k) end[k] = end[std::size_t(levels)];
}

}  // namespace

Subcycles::Subcycles(const Model& md, int max_ratio)
    : max_levels_(std::countr_zero(unsigned(max_ratio))), point_cell_(md.m, -1), particle_class_(md.n, 0),
      cell_class_(md.cells, 0), touched_(md.n, 0), counts_(kForceStride * md.n, 0), all_cells_(md.cells),
      boundary_(md.boundary_points), interior_(md.interior_points) {
  for (std::size_t c = 0; c < md.cells; ++c) all_cells_[c] = std::int32_t(c);
  cells_ = all_cells_;  // (sorted by class at each plan: every cell and point once, in some order)
  for (std::size_t c = 0; c < md.cells; ++c)
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g) point_cell_[std::size_t(g)] = std::int32_t(c);
  // each cell's particles: the union of its points' rows, each once (the points share most of them)
  std::vector<std::int32_t> seen(md.n, -1);
  support_offsets_.assign(md.cells + 1, 0);
  for (std::size_t c = 0; c < md.cells; ++c) {
    for (auto g = md.cell_points[c]; g < md.cell_points[c + 1]; ++g)
      for (auto k = md.nbr_offsets[std::size_t(g)]; k < md.nbr_offsets[std::size_t(g) + 1]; ++k)
        if (const std::int32_t I = md.nbr[std::size_t(k)]; seen[std::size_t(I)] != std::int32_t(c)) {
          seen[std::size_t(I)] = std::int32_t(c);
          support_.push_back(I);
        }
    support_offsets_[c + 1] = std::int64_t(support_.size());
  }
}

void Subcycles::plan(const Model& md, const std::vector<double>& dt_cell, double dt, int levels, std::int64_t step,
                     const SumOverRanks& sum, const LargestOverRanks& largest) {
  start_ = step;
  if (levels == 0) {  // a cycle of one step (every rank's: levels is agreed): every particle and cell due
    levels_ = 0;
    std::fill(particle_class_.begin(), particle_class_.end(), std::int8_t(0));
    std::fill(cell_class_.begin(), cell_class_.end(), std::int8_t(0));
    std::fill(touched_.begin(), touched_.end(), std::int8_t(0));
    cells_end_.assign(std::size_t(kMaxLevels) + 1, cells_.size());
    boundary_end_.assign(std::size_t(kMaxLevels) + 1, boundary_.size());
    interior_end_.assign(std::size_t(kMaxLevels) + 1, interior_.size());
    return;
  }
  static_assert(kForceStride == kMaxLevels, "a particle's counts: one per class below the largest");
  // each cell counts its limit class at every particle of its points' rows; the least counted is the particle's
  std::fill(counts_.begin(), counts_.end(), 0);
  for (std::size_t c = 0; c < md.cells; ++c) {
    int limit = 0;
    while (limit < levels && double(2 << limit) * dt <= dt_cell[c]) ++limit;
    if (limit == levels) continue;  // (no particle's class is counted past the cycle's)
    for (auto k = support_offsets_[c]; k < support_offsets_[c + 1]; ++k)
      ++counts_[kForceStride * std::size_t(support_[std::size_t(k)]) + std::size_t(limit)];
  }
  for (std::size_t I = 0; I < md.n; ++I)  // (every copy of a shared particle holds the same contact force)
    if (touched_[I]) ++counts_[kForceStride * I], touched_[I] = 0;
  sum(counts_);
  for (std::size_t I = 0; I < md.n; ++I) {
    int k = 0;
    while (k < levels && counts_[kForceStride * I + std::size_t(k)] == 0) ++k;
    particle_class_[I] = std::int8_t(k);
  }
  // the cycle no longer than its largest class needs (a part all at the smallest step: one step), so
  // frames, history rows and checkpoints are not held back for nothing
  int top = 0;
  for (std::size_t I = 0; I < md.n; ++I) top = std::max(top, int(particle_class_[I]));
  levels = levels_ = largest(top);
  for (std::size_t c = 0; c < md.cells; ++c) {
    int k = levels;
    for (auto j = support_offsets_[c]; j < support_offsets_[c + 1] && k > 0; ++j)
      k = std::min(k, int(particle_class_[std::size_t(support_[std::size_t(j)])]));
    cell_class_[c] = std::int8_t(k);
  }
  sort_by_class(all_cells_, [&](std::int32_t c) { return cell_class_[std::size_t(c)]; }, levels, cells_, cells_end_);
  auto point_class = [&](std::int32_t g) { return cell_class_[std::size_t(point_cell_[std::size_t(g)])]; };
  sort_by_class(md.boundary_points, point_class, levels, boundary_, boundary_end_);
  sort_by_class(md.interior_points, point_class, levels, interior_, interior_end_);
}

int Subcycles::level(std::int64_t step) const {
  const std::int64_t offset = step - start_;
  return offset == 0 ? levels_ : std::min(levels_, std::countr_zero(std::uint64_t(offset)));
}

void Subcycles::touch(const std::vector<double>& contact_force) {
  for (std::size_t I = 0; I < touched_.size(); ++I)
    touched_[I] |= std::int8_t(contact_force[3 * I] != 0 || contact_force[3 * I + 1] != 0 || contact_force[3 * I + 2] != 0);
}

}  // namespace rk
