// The coupled cycle of DESIGN.md / paper section 8, driven by the coupler (docs/protocol.md):
//   cycle n (t^n -> t^n + dt):  DtDecision -> both;  solid advances, sends InterfaceFaces and DtProposal;
//   faces -> fluid;  fluid samples, sends FluidSamples;  interface conditions;  InterfaceStates -> fluid and
//   solid;  DtProposal <- fluid (pipelined scheme: before its advance, so the next DtDecision, and the solid's
//   next step, overlap the fluid's advance; sequential: after it);  OutputRequest when an output time is
//   reached;  next dt = min of proposals.
// Cycle 0 is the initial exchange with dt = 0 (nobody advances): the solid gets its first interface pressure.
#pragma once

#include <filesystem>

#include "common/checkpoint/part_file.h"
#include "coupler/coupler_config.h"
#include "coupler/history.h"
#include "coupler/hub.h"

namespace cosim::coupler {

struct RunSummary {
  int code = 0;  // 0 completed, 5 peer or protocol failure, 4 I/O, 130 interrupted
  std::string status = "completed", message;
  long cycles = 0;
  double time = 0;
  CycleTiming total;  // sums over the cycles
};

// Where the run's checkpoint sets go and what their manifests record; `restart`: the set this run resumes from.
struct CheckpointContext {
  std::filesystem::path root;                       // the sets' directory (RUN/checkpoints)
  const checkpoint::PartReader* restart = nullptr;  // the coupler's part of the set resumed from; null: a fresh start
  std::string scene_file;  // the scene as read (its text goes into each manifest), with its overrides
  std::vector<std::string> overrides;
  std::string scene_hash;
};
inline constexpr const char* kCouplerPart = "coupler.h5";

// Handshakes and runs to t_end; on any failure stops both solvers with a reason and returns a non-zero code.
// With cfg.checkpoint enabled, writes a checkpoint set when one is due (docs/protocol.md, "Checkpoints").
RunSummary run_coupled(const CouplerConfig& cfg, Hub& hub, const std::filesystem::path& out_dir,
                       const CheckpointContext& ck = {});

// The next step: min of the proposals and dt_max, shortened so that no output time is stepped over and no
// step is tiny (as common/app/run_driver.h).
double choose_dt(double proposal_min, double dt_max, double t, double t_next_output);

}  // namespace cosim::coupler
