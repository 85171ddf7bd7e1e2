// What a restart may and may not change in the scene (cosim run --restart): a checkpoint set holds the state of
// the scene it was written with, so every key that shapes the physics must be the same; the end time, how often to
// checkpoint, the timeouts, threads and the programs may change.
#pragma once

#include <string>
#include <vector>

#include "common/config/config.h"

namespace cosim::launcher {

struct SceneChange {
  std::string key;       // a.b.c or a.b[2]
  std::string was, now;  // the values ("(absent)" when missing)
};

// The keys whose values differ between the scene of the set and the scene given now, less those a restart may
// change (restart_may_change). Numbers compare by value (1e5 equals 100000.0).
std::vector<SceneChange> physics_changes(const config::Node& was, const config::Node& now);

// True for the keys a restart may change: the end times and max_cycles, the checkpoint sections, the coupler's
// timeouts, threads, the launcher's programs and the scene's name.
bool restart_may_change(const std::string& key);

}  // namespace cosim::launcher
