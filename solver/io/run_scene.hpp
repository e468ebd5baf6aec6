// The scene a run started with, kept beside its checkpoints (CASE/checkpoint/run.yaml: its --set values
// and the scene they resolved to), so that `rksolve CASE --restart` goes on with that run's scene. A
// restart used to read scene.resolved.yaml with only its own --set values: the first run's were dropped
// (a run at one rate and a 2-us frame interval went on at 16x and 10 us, exit 0), and an edited or
// overridden material changed the run half-way without a word.
#pragma once
#include <string>
#include <vector>

#include "scene.hpp"

namespace rk {

// The run's record (rank 0; the checkpoint folder made if needed): a fresh run's, and a restart's with
// the sets restart_scene gave, so that the next restart goes on with its end, intervals and bounds.
void write_run_scene(const std::string& case_dir, const Scene& scene, const std::vector<Override>& overrides);

// The scene a restart goes on with: scene.resolved.yaml with the run's recorded --set values, then the
// restart's own. The restart's may change only the keys that do not change the answer so far
// (restart_may_change: the end, the output and checkpoint intervals, the health bounds); any other key
// that differs from the run's, by an edit of scene.resolved.yaml or a --set, is an error naming it.
// `sets` gets the --set values the restart goes on with, the run's then its own, each key once.
Scene restart_scene(const std::string& case_dir, const std::vector<Override>& overrides, std::vector<Override>& sets);

// Whether a restart may change `key` (a dotted path).
bool restart_may_change(const std::string& key);

}  // namespace rk
