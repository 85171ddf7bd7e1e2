// What kind of run a scene is: coupled when it has a solid: section, else fluid-only. A coupling: section without a
// solid is refused (its time and output would be half read by a fluid-only run).
#pragma once

#include "common/config/config.h"

namespace cosim::app {

// Throws config::ConfigError naming the file, line and key when `root` has coupling: but no solid:.
inline void refuse_coupling_without_solid(const config::Node& root) {
  if (root.has("coupling") && !root.has("solid"))
    throw config::ConfigError(
        root.where("coupling") +
        ": needs a solid: section (a coupled run); for a fluid-only run remove coupling: and put time: and output: "
        "under fluid:");
}

}  // namespace cosim::app
