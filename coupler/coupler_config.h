// The `coupling:` section of a scene (the coupler reads only this section; the others belong to the solvers).
//   coupling:
//     mode: robin                # robin | impedance | characteristic | standard (interface_conditions.h)
//     time: {end: 0.37, max_cycles: 1000000, dt_max: 1.0e-3}   # [s], [-], [s] (dt_max optional)
//     output: {interval: 0.005}  # [s] or times: [...]; snapshot requests to both solvers
//     timeout: 5.0               # [s] a peer silent for longer is declared dead
//     heartbeat_interval: 0.5    # [s] (default: timeout / 10)
//     connect_timeout: 30.0      # [s] to wait for both solvers' Hello
//     scheme: pipelined          # pipelined | sequential: order of the cycle (docs/protocol.md, "Schemes")
//     predictor: linear          # linear | none: fluid pressures extrapolated to the solid's time (cycle.h)
//     checkpoint: {interval: 1.0e-3, cycles: 500, keep: 2}   # whole-run checkpoint sets (checkpoint_sets.h)
#pragma once

#include <string>
#include <vector>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/coupling/types.h"

namespace cosim::coupler {

struct CouplerConfig {
  coupling::Mode mode = coupling::Mode::Robin;
  coupling::Scheme scheme = coupling::Scheme::Pipelined;
  double t_end = 0.0;
  long max_cycles = 1000000000L;
  double dt_max = 0.0;               // 0: no limit
  std::vector<double> output_times;  // sorted, ends with t_end
  double timeout = 3.0;
  double heartbeat_interval = 0.5;
  double connect_timeout = 30.0;
  double step_timeout = 0.0;  // 0: automatic (HubOptions)
  double max_message_mb = 256.0;
  bool pressure_predictor = true;           // predictor: linear
  checkpoint::CheckpointPolicy checkpoint;  // off unless coupling.checkpoint is given
  // Fault injection for tests only (coupler --stall-after-cycle N --stall-seconds S, hidden): the main thread
  // sleeps after cycle N, as a coupler busy with a large message would; its heartbeat thread goes on.
  long stall_after_cycle = -1;
  double stall_seconds = 0.0;
};

// Throws config::ConfigError naming the file, line and key.
CouplerConfig read_coupler_config(const std::string& file, const std::vector<std::string>& overrides);

}  // namespace cosim::coupler
