// The standalone fluid run: scene -> snapshots at the output times -> summary.json.
#pragma once

#include "common/app/run_options.h"

namespace cosim::fluid {

using app::RunOptions;

// Exit codes: 0 success, 2 bad input (scene, options), 3 inadmissible state / numerical failure,
// 4 I/O failure, 130 interrupted.
// With opt.coupler set, run_fluid is the coupled run (coupled_runner.cpp): exit codes as above, plus 5 for a
// coupling failure (coupler lost, refused, protocol error).
int run_fluid(const RunOptions& opt);
int run_fluid_coupled(const RunOptions& opt);

}  // namespace cosim::fluid
