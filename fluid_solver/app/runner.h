// The standalone fluid run: scene -> snapshots at the output times -> summary.json.
#pragma once

#include "common/app/run_options.h"

namespace cosim::fluid {

using app::RunOptions;

// Exit codes: 0 success, 2 bad input (scene, options), 3 inadmissible state / numerical failure,
// 4 I/O failure, 130 interrupted.
int run_fluid(const RunOptions& opt);

}  // namespace cosim::fluid
