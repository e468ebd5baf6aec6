#include "stage_link.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "error.hpp"
#include "text_file.hpp"

namespace rk {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StageLink, from, start, die_start, continues, dwell)

void write_stage_link(const std::string& case_dir, const StageLink& link) {
  write_text_file(case_dir + "/" + kStageLinkFile, nlohmann::json(link).dump(2) + "\n");
}

bool read_stage_link(const std::string& case_dir, StageLink& link) {
  const std::string path = case_dir + "/" + kStageLinkFile;
  if (!std::filesystem::exists(path)) return false;
  std::ifstream in(path);
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw Error(path + ": not a JSON object (a damaged file?)");
  try {
    link = j.get<StageLink>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": " + e.what());
  }
  return true;
}

}  // namespace rk
