#include "io/run_scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "error.hpp"
#include "io/checkpoint.hpp"
#include "text_file.hpp"

namespace rk {
namespace {

constexpr const char* kRunScene = "/checkpoint/run.yaml";
using Keys = std::map<std::string, std::string>;  // dotted path -> the value in flow style

void flatten(const YAML::Node& n, const std::string& path, Keys& out) {
  const auto below = [&](const std::string& k) { return path.empty() ? k : path + "." + k; };
  if (n.IsMap()) {
    for (const auto& kv : n) flatten(kv.second, below(kv.first.as<std::string>()), out);
  } else if (n.IsSequence() && std::any_of(n.begin(), n.end(), [](const YAML::Node& e) { return e.IsMap(); })) {
    for (std::size_t i = 0; i < n.size(); ++i) flatten(n[i], path + "[" + std::to_string(i) + "]", out);
  } else {
    YAML::Emitter e;
    e.SetMapFormat(YAML::Flow), e.SetSeqFormat(YAML::Flow);
    e << n;
    out[path] = e.c_str();
  }
}

Keys keys_of(const YAML::Node& n) {
  Keys k;
  flatten(n, "", k);
  return k;
}

// "key 'a.b' = X where the run started with Y" for the keys that differ and a restart may not change
std::string changed(const Keys& started, const Keys& now) {
  std::string said;
  int count = 0;
  Keys all = started;
  all.insert(now.begin(), now.end());
  for (const auto& [key, _] : all) {
    const auto a = started.find(key), b = now.find(key);
    const std::string was = a == started.end() ? "(none)" : a->second, is = b == now.end() ? "(none)" : b->second;
    if (was == is || restart_may_change(key)) continue;
    if (count++ < 3) said += std::string(said.empty() ? "" : "; ") + "key '" + key + "' = " + is + " where the run started with " + was;
  }
  if (count > 3) said += "; and " + std::to_string(count - 3) + " more";
  return said;
}

// `earlier` then `later`, each path once, with its last value (in the order first given)
std::vector<Override> merged_sets(const std::vector<Override>& earlier, const std::vector<Override>& later) {
  std::vector<Override> all;
  for (const auto* list : {&earlier, &later})
    for (const Override& o : *list) {
      const auto at = std::find_if(all.begin(), all.end(), [&](const Override& a) { return a.path == o.path; });
      if (at == all.end()) all.push_back(o);
      else at->value = o.value;
    }
  return all;
}

}  // namespace

bool restart_may_change(const std::string& key) {
  return key == "time.end" || key == "time.output_interval" || key == "output.checkpoint_steps" ||
         key == "output.checkpoint_minutes" || key.rfind("health.", 0) == 0;
}

void write_run_scene(const std::string& case_dir, const Scene& scene, const std::vector<Override>& overrides) {
  std::filesystem::create_directories(case_dir + "/checkpoint");
  YAML::Emitter e;
  e << YAML::BeginMap << YAML::Key << "sets" << YAML::Value << YAML::BeginSeq;
  for (const Override& o : overrides) e << o.path + "=" + o.value;
  e << YAML::EndSeq << YAML::Key << "scene" << YAML::Value << YAML::Load(scene.resolved_yaml) << YAML::EndMap;
  write_text_file(case_dir + kRunScene, "# rksolve: the run the checkpoints continue (its --set values and its scene)\n" +
                                            std::string(e.c_str()) + "\n");
}

Scene restart_scene(const std::string& case_dir, const std::vector<Override>& overrides, std::vector<Override>& sets) {
  const std::string path = case_dir + kRunScene, file = case_dir + "/scene.resolved.yaml";
  if (!std::filesystem::exists(path)) {
    const std::string first = checkpoint_path(case_dir, 0);
    if (!std::filesystem::exists(first) && !std::filesystem::exists(first + ".previous"))  // nothing to restart from: said later
      return sets = overrides, load_scene(file, overrides, Side::solve);
    throw Error(path + ": not found: the checkpoints hold no record of their run's scene (an older rksolve wrote them); "
                       "run without --restart to start anew");
  }
  YAML::Node run;
  std::vector<Override> recorded;
  try {
    run = YAML::LoadFile(path);
    for (const auto& s : run["sets"]) recorded.push_back(parse_override(s.as<std::string>()));
  } catch (const YAML::Exception& e) {
    throw Error(path + ": unreadable (" + e.what() + "); run without --restart to start anew");
  }
  const Keys started = keys_of(run["scene"]);
  const std::string edited = changed(started, keys_of(YAML::Load(load_scene(file, recorded, Side::solve).resolved_yaml)));
  if (!edited.empty())
    throw Error(file + ": " + edited + " (" + path + "): a restart goes on with its run's scene; undo the edit, or "
                "run without --restart to start anew");
  sets = merged_sets(recorded, overrides);
  Scene scene = load_scene(file, sets, Side::solve);
  const std::string set = changed(started, keys_of(YAML::Load(scene.resolved_yaml)));
  if (!set.empty())
    throw Error("--set: " + set + ": a restart goes on with its run's scene and may change only time.end, "
                "time.output_interval, output.checkpoint_steps, output.checkpoint_minutes and health.*; run without "
                "--restart to change it");
  return scene;
}

}  // namespace rk
