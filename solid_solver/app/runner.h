// The standalone solid run: scene -> snapshots at the output times -> summary.json.
#pragma once

#include "common/app/run_options.h"

namespace cosim::solid {

using app::RunOptions;

// Exit codes (as fluid_solver): 0 success, 2 bad input, 3 numerical failure, 4 I/O failure, 130 interrupted.
// With opt.coupler set, run_solid is the coupled run (coupled_runner.cpp; exit code 5: coupling failure).
int run_solid(const RunOptions& opt);
int run_solid_coupled(const RunOptions& opt);

}  // namespace cosim::solid
