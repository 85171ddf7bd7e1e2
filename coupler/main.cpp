// coupler SCENE.yaml --endpoint EP [--token T] [--out DIR] [--set key=value ...] [--transcript FILE] [--quiet]
//         [--checkpoints ROOT] [--restart SET]
// Reads the scene's `coupling:` section, binds EP, handshakes the fluid and solid solvers and runs the coupled
// cycle (coupler/cycle.h). Exit codes: 0 completed, 2 bad input, 4 I/O, 5 peer or protocol failure,
// 130 interrupted. A failure caused by a peer names it in coupler_summary.json ("peer": fluid or solid): the
// launcher blames that process, not the coupler that stopped the run.
#include <fmt/format.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/app/cli_suggest.h"
#include "common/app/plan_facts.h"
#include "common/app/run_driver.h"
#include "common/app/run_options.h"
#include "common/app/version.h"
#include "common/checkpoint/checkpoint_sets.h"
#include "common/checkpoint/part_file.h"
#include "common/config/config.h"
#include "common/coupling/errors.h"
#include "common/coupling/scene_hash.h"
#include "common/io/atomic_file.h"
#include "coupler/coupler_config.h"
#include "coupler/cycle.h"
#include "coupler/hub.h"
#include "coupler/transcript.h"

using namespace cosim;

namespace {
void write_summary(const std::filesystem::path& dir, const coupler::RunSummary& s, coupling::Scheme scheme,
                   const coupler::Hub& hub) {
  const std::string& peer = hub.blamed();
  const double n = std::max<long>(s.cycles, 1);
  nlohmann::json j;
  j["status"] = s.status;
  j["version"] = cosim::app::version();
  j["git_commit"] = cosim::app::git_commit();
  j["scheme"] = coupling::scheme_name(scheme);  // pipelined: solid and fluid work overlap (CycleTiming::comm)
  j["message"] = s.message;
  j["exit_code"] = s.code;
  if (s.code != 0 && !peer.empty()) j["peer"] = peer;  // the solver whose failure stopped the run
  j["cycles"] = s.cycles;
  j["time"] = s.time;
  j["per_cycle_seconds"] = {{"wall", s.total.wall / n},     {"solid", s.total.solid / n},
                            {"fluid", s.total.fluid / n},   {"coupler", s.total.coupler / n},
                            {"output", s.total.output / n}, {"comm", s.total.comm() / n}};
  j["comm_fraction"] = s.total.wall > 0 ? s.total.comm() / s.total.wall : 0.0;
  // The encoded envelopes of the data messages after the handshake, whole run [bytes] (ZeroMQ framing not counted).
  for (const coupling::Role r : {coupling::Role::Fluid, coupling::Role::Solid})
    j["message_bytes"][coupling::role_name(r)] = {{"received", hub.peer(r).bytes_received},
                                                  {"sent", hub.peer(r).bytes_sent}};
  // Each solver as its Hello described it (a hand-started `mpirun -np N fluid_solver` included).
  for (const coupling::Role r : {coupling::Role::Fluid, coupling::Role::Solid})
    if (const coupler::Peer& p = hub.peer(r); p.connected)
      j["peers"][coupling::role_name(r)] = {{"program", p.program}, {"pid", p.pid}, {"ranks", p.ranks}};
  io::write_file_atomically(dir / "coupler_summary.json", j.dump(2) + "\n");  // whole, or the earlier one
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"coupler: interface conditions, time step and routing between fluid_solver and solid_solver"};
  std::string scene, endpoint, token, out = ".", transcript;
  std::vector<std::string> overrides;
  bool quiet = false;
  app.add_option("scene", scene, "scene file (YAML); only its coupling: section is read")->required();
  app.add_option("--endpoint", endpoint,
                 "ZeroMQ endpoint to bind: ipc://PATH or tcp://HOST:PORT (required unless --check)");
  bool check = false;
  app.add_flag("--check", check, "validate the scene's coupling section, run nothing, write nothing (exit 0 or 2)");
  bool plan_facts = false;  // cosim check's (common/app/plan_facts.h): not in --help
  app.add_flag("--plan-facts", plan_facts)->group("");
  app.add_option("--token", token, "per-run token the solvers must present (default: $COSIM_TOKEN)");
  app.add_option("--out", out, "output directory (interface_history.csv, timing.csv, coupler_summary.json)");
  app.add_option("--set", overrides, "override a scene value: key.path=value (repeatable)");
  app.add_option("--transcript", transcript, "write every message in protobuf text form to FILE");
  app.add_flag("--quiet", quiet, "only warnings and errors");
  std::string restart, checkpoints;
  app.add_option("--restart", restart, "resume from this checkpoint set (RUN/checkpoints/NNNNNNNNN)");
  app.add_option("--checkpoints", checkpoints, "directory of the run's checkpoint sets (default OUT/checkpoints)");
  long stall_after_cycle = -1;
  double stall_seconds = 0.0;  // tests only (CouplerConfig::stall_after_cycle): not in --help
  app.add_option("--stall-after-cycle", stall_after_cycle)->group("");
  app.add_option("--stall-seconds", stall_seconds)->group("");
  app.set_version_flag("--version", cosim::app::version_line("coupler"));
  app.footer(
      "Examples:\n"
      "  cosim run configs/piston_2d.yaml      the usual way: cosim starts the coupler and both solvers\n"
      "  coupler configs/piston_2d.yaml --endpoint ipc:///tmp/piston.sock --token T --out runs/piston/coupler\n"
      "      then: fluid_solver|solid_solver configs/piston_2d.yaml --out DIR --coupler ipc:///tmp/piston.sock "
      "--token T");
  if (const std::string unknown = cosim::app::unknown_option(app, argc, argv); !unknown.empty()) {
    std::cerr << "coupler: " << unknown << "\nRun with --help for more information.\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) { return app.exit(e) == 0 ? 0 : 2; }
  auto logger = spdlog::stderr_color_mt("coupler");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("[coupler] %l: %v");
  if (quiet) spdlog::set_level(spdlog::level::warn);
  app::install_interrupt_handlers();

  coupler::CouplerConfig cfg;
  coupler::HubOptions ho;
  try {
    cfg = coupler::read_coupler_config(scene, overrides);
    cfg.stall_after_cycle = stall_after_cycle;
    cfg.stall_seconds = stall_seconds;
    ho.scene_hash = coupling::scene_hash(scene, overrides);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (check) {  // the plan line cosim check prints
    std::cout << fmt::format("coupler: {} interface conditions, {} cycle, end time {:g} s, {} output time(s), {}\n",
                             coupling::mode_name(cfg.mode), coupling::scheme_name(cfg.scheme), cfg.t_end,
                             cfg.output_times.size(), checkpoint::describe(cfg.checkpoint));
    if (plan_facts) cosim::app::print_plan_facts({{"end_time", cfg.t_end}, {"dt_max", cfg.dt_max}});
    return 0;
  }
  if (endpoint.empty()) {
    spdlog::error("--endpoint is required (the ZeroMQ endpoint to bind; or --check to validate the scene only)");
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) {
    spdlog::error("{}: cannot create the output directory: {}", out, ec.message());
    return 4;
  }
  ho.endpoint = endpoint;
  ho.token = token.empty() ? cosim::app::token_from_environment() : token;
  ho.mode = cfg.mode;
  ho.scheme = cfg.scheme;
  ho.timeout = cfg.timeout;
  ho.heartbeat_interval = cfg.heartbeat_interval;
  ho.connect_timeout = cfg.connect_timeout;
  ho.step_timeout = cfg.step_timeout;
  ho.max_message_bytes = cfg.max_message_mb * 1024 * 1024;
  std::optional<checkpoint::PartReader> restart_part;
  if (!restart.empty()) {
    try {  // its cycle is the one both solvers' Hellos must name
      restart_part.emplace(checkpoint::open_verified_part(restart, coupler::kCouplerPart, "coupler"));
      ho.restarted_from = restart_part->integer("cycle");
    } catch (const std::exception& e) {
      spdlog::error("--restart {}: {}", restart, e.what());
      return 2;
    }
  }
  const coupler::CheckpointContext ck{
      checkpoints.empty() ? std::filesystem::path(out) / "checkpoints" : std::filesystem::path(checkpoints),
      restart_part ? &*restart_part : nullptr, scene, overrides, ho.scene_hash};
  try {
    coupler::Transcript tr(transcript);
    coupler::Hub hub(ho, transcript.empty() ? nullptr : &tr);
    spdlog::info("listening on {} ({} coupling, {} cycle, timeout {:g} s)", hub.bound_endpoint(),
                 coupling::mode_name(cfg.mode), coupling::scheme_name(cfg.scheme), cfg.timeout);
    const coupler::RunSummary s = coupler::run_coupled(cfg, hub, out, ck);
    write_summary(out, s, cfg.scheme, hub);
    if (s.code == 0) {
      const double n = std::max<long>(s.cycles, 1);
      spdlog::info(
          "{}; per cycle: wall {:.3g} ms, solid {:.3g} ms, fluid {:.3g} ms, coupler {:.3g} ms, "
          "communication {:.3g} ms ({:.1f}% of wall)",
          s.message, 1e3 * s.total.wall / n, 1e3 * s.total.solid / n, 1e3 * s.total.fluid / n,
          1e3 * s.total.coupler / n, 1e3 * s.total.comm() / n,
          s.total.wall > 0 ? 100.0 * s.total.comm() / s.total.wall : 0.0);
    }
    return s.code;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 4;
  }
}
