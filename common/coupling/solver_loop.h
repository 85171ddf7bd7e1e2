// The loop every solver runs in a coupled run: the coupler owns time, so the solver only obeys its
// directives (docs/protocol.md, "Writing a solver client"). The solver supplies the cycle (its part of
// paper section 8 for one DtDecision) and the snapshot writer; this maps every failure to an exit code
// and tells the coupler why when the fault is ours:
//   0 completed (the coupler's Stop), 2 bad input, 3 numerical failure of this solver, 4 I/O,
//   5 coupling failure (peer lost, refused, protocol error, malformed data), 1 any other (unforeseen) failure,
//   130 interrupted (common/app/errors.h).
#pragma once

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <memory>
#include <vector>

#include "common/app/run_driver.h"
#include "common/app/run_options.h"
#include "common/coupling/client.h"
#include "common/coupling/scene_hash.h"

namespace cosim::coupling {

// Connects the solver of a coupled run (opt.coupler, opt.token) to its coupler: handshake with the scene hash
// of the same file and overrides. Logs and returns null when that fails (the caller exits with 5).
// A fluid names its phases and the lowest pressure each admits; a restarted solver passes the cycle and time of
// the set it restored; a solver on several MPI ranks connects from rank 0 alone and says how many ranks it speaks
// for (Hello.ranks).
struct SolverPhases {
  std::vector<std::string> names;
  std::vector<double> min_pressure;  // [Pa]
};
inline std::unique_ptr<Client> connect_solver(const app::RunOptions& opt, Role role, const std::string& program,
                                              SolverPhases phases = {}, long restarted_from = 0,
                                              double restart_time = 0, int ranks = 1) {
  ClientOptions co;
  co.ranks = static_cast<std::uint32_t>(ranks);
  co.endpoint = opt.coupler;
  co.token = opt.token;
  co.role = role;
  co.program = program;
  co.phase_names = std::move(phases.names);
  co.phase_min_pressure = std::move(phases.min_pressure);
  co.restarted_from = restarted_from;
  co.restart_time = restart_time;
  co.should_stop = [] { return app::interrupted(); };  // SIGINT/SIGTERM end a wait on a silent coupler at once
  try {
    co.scene_hash = scene_hash(opt.scene_file, opt.overrides);
    return std::make_unique<Client>(co);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return nullptr;
  }
}

struct SolverLoopResult {
  std::string status = "completed";  // completed | failed | interrupted
  std::string error;
  int code = 0;
  double wall = 0;  // [s]
  long cycles = 0;  // DtDecisions obeyed
  int snapshots = 0;
  int checkpoints = 0;
};

// cycle(const Directive&) runs one coupled cycle (Advance); output(const Directive&) writes snapshot
// d.output_index; checkpoint(const Directive&) writes this solver's part into d.directory and returns its file
// name there (the loop confirms it to the coupler). Solver time and the coupler's t^n are compared at every cycle.
// `client`: a Client, or a RankRelay for a solver on several ranks (every rank runs the loop).
template <class Link, class Solver, class Cycle, class Output, class Checkpoint>
SolverLoopResult run_solver_loop(Link& client, const Solver& sim, Cycle&& cycle, Output&& output,
                                 Checkpoint&& checkpoint) {
  SolverLoopResult r;
  const auto t0 = std::chrono::steady_clock::now();
  const auto fail = [&](int code, const std::string& status, const std::string& msg, bool tell) {
    r.code = code;
    r.status = status;
    r.error = msg;
    if (tell) client.report_error(msg);
    spdlog::error("{}", msg);
  };
  try {
    for (;;) {
      if (app::interrupted()) throw std::runtime_error("interrupted");
      const Directive d = client.next();
      if (d.kind == Directive::Kind::Stop) {
        spdlog::info("coupler: {}", d.reason);
        break;
      }
      const auto seconds_since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
      };
      if (d.kind == Directive::Kind::Output) {
        const auto t_out = std::chrono::steady_clock::now();
        output(d);
        client.add_output_seconds(seconds_since(t_out));
        ++r.snapshots;
        continue;
      }
      if (d.kind == Directive::Kind::Checkpoint) {
        const auto t_out = std::chrono::steady_clock::now();
        const std::string part = checkpoint(d);
        client.add_output_seconds(seconds_since(t_out));
        std::error_code ec;
        const auto bytes = std::filesystem::file_size(std::filesystem::path(d.directory) / part, ec);
        client.confirm_checkpoint(part, ec ? 0 : bytes);
        ++r.checkpoints;
        continue;
      }
      const double scale = std::max({std::abs(d.time), std::abs(sim.time()), d.dt, 1e-300});
      if (std::abs(sim.time() - d.time) > 1e-9 * scale)
        throw ProtocolError(
            fmt::format("DtDecision of cycle {} starts at t = {:.12g} s but this solver is at t = "
                        "{:.12g} s",
                        d.cycle, d.time, sim.time()));
      cycle(d);
      ++r.cycles;
    }
  } catch (const CouplingError& e) {
    fail(app::interrupted() ? 130 : 5, app::interrupted() ? "interrupted" : "failed", e.what(), false);
  } catch (const std::invalid_argument& e) {  // malformed data from the coupler
    fail(5, "failed", e.what(), true);
  } catch (const std::exception& e) {
    // The typed failures of common/app/errors.h keep their code; any other is 1 (unforeseen), not hidden as I/O.
    const int code = app::exit_code_of(e);
    if (code != app::kExitUnforeseen) fail(code, "failed", e.what(), true);
    else if (app::interrupted()) fail(130, "interrupted", "interrupted", true);
    else fail(code, "failed", fmt::format("unforeseen failure: {}", e.what()), true);
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  client.close();
  return r;
}

}  // namespace cosim::coupling
