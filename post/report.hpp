// CASE/report.md: what was run (scene, resolution, ranks), what it cost (wall time and its phases)
// and whether to trust it (energy balance verdict, final energies, die forces), in one page.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rk {

// CASE/prep.json, with its rank count: one error naming the file where it is missing or not rkprep's.
nlohmann::json read_prep_json(const std::string& case_dir);

// `fill`: a line per die on its fill at the last frame (post/die_fill_regions.hpp), or none
// fill: the dies' unfilled regions at the last frame; folds: the folds found (null: not looked for)
// skipped: rkpost's messages on the frames it could not merge (each a warning row)
void write_report(const std::string& case_dir, const std::vector<std::string>& fill = {},
                  const std::vector<std::string>* folds = nullptr, const std::vector<std::string>& skipped = {});

}  // namespace rk
