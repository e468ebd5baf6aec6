#include "stage_link.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "error.hpp"
#include "hash.hpp"
#include "text_file.hpp"

namespace rk {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StageLink, from, start, die_start, continues, dwell)

void write_stage_link(const std::string& case_dir, const StageLink& link) {
  nlohmann::json j = link;
  // and where it lies from this case: a chain moved or copied as a whole finds its own stages
  // (lexically, as it is read back: fs::relative would resolve a symlinked case folder first)
  j["from_relative"] =
      std::filesystem::path(link.from).lexically_relative(std::filesystem::absolute(case_dir).lexically_normal()).string();
  j["from_solve"] = link.from_solve;
  write_text_file(case_dir + "/" + kStageLinkFile, j.dump(2) + "\n");
}

std::string solve_record_hash(const std::string& case_dir) {
  const std::string path = case_dir + "/solve.json";
  return std::filesystem::exists(path) ? file_hash(path) : "";
}

bool read_stage_link(const std::string& case_dir, StageLink& link) {
  const std::string path = case_dir + "/" + kStageLinkFile;
  if (!std::filesystem::exists(path)) return false;
  std::ifstream in(path);
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw Error(path + ": not a JSON object (a damaged file?)");
  try {
    link = j.get<StageLink>();
    // the previous stage beside this one, where the chain was moved or copied whole (the recorded
    // absolute path is then gone, or the original chain's)
    if (j.contains("from_solve")) link.from_solve = j.at("from_solve").get<std::string>();
    if (j.contains("from_relative")) {
      const auto beside = (std::filesystem::absolute(case_dir) / j.at("from_relative").get<std::string>()).lexically_normal();
      if (std::filesystem::is_directory(beside)) link.from = beside.string();
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": " + e.what());
  }
  return true;
}

}  // namespace rk
