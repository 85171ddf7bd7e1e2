// The standalone solid run: scene -> snapshots at the output times -> summary.json.
#pragma once

#include "common/app/run_options.h"

namespace cosim::solid {

using app::RunOptions;

// Exit codes (as fluid_solver): 0 success, 2 bad input, 3 numerical failure, 4 I/O failure, 130 interrupted.
int run_solid(const RunOptions& opt);

}  // namespace cosim::solid
