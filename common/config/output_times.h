// The `output` section keys shared by the solvers: `interval` [s] and `times` [s].
#pragma once

#include <vector>

#include "common/config/config.h"

namespace cosim::config {

// Reads interval/times from `out` (may be null: no section) and returns the sorted, unique output
// times in (0, t_end], always ending with t_end. Does not call out->finish().
std::vector<double> read_output_times(Node* out, double t_end);

}  // namespace cosim::config
