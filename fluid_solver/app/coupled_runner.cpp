// The fluid's coupled run (paper section 8; docs/protocol.md): the coupler decides every step and every
// snapshot; each cycle the solid's faces become this cycle's embedded boundary, the fluid is sampled next
// to them, and the interface states of the coupler set the wall velocity of the step.
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include "common/app/rank_failure.h"
#include "common/coupling/client.h"
#include "common/coupling/rank_relay.h"
#include "common/coupling/scene_hash.h"
#include "common/coupling/solver_loop.h"
#include "common/parallel/mpi/rank_watchdog.h"
#include "fluid_solver/app/block_setup.h"
#include "fluid_solver/app/fluid_checkpoint.h"
#include "fluid_solver/app/run_summary.h"
#include "fluid_solver/app/runner.h"
#include "fluid_solver/coupled/coupled_boundary.h"
#include "fluid_solver/io/fluid_output.h"
#include "fluid_solver/parallel/block_io.h"

namespace cosim::fluid {

int run_fluid_coupled(const RunOptions& opt, const parallel::MpiSession& mpi) {
  const bool root = mpi.rank() == 0;
  auto loaded = app::load_scene<FluidScene>(opt, load_fluid_scene);
  if (!loaded) return 2;
  FluidScene scene = std::move(*loaded);
  if (!scene.embedded.bodies.empty()) {
    spdlog::error(
        "{}: fluid.embedded.bodies: a coupled run takes its embedded boundary from the solid; remove the "
        "bodies or run the fluid alone",
        opt.scene_name());
    return 2;
  }
  // The mesh over the ranks (one block on one rank); each block cuts the interface over its cells and samples the
  // faces centred in it; rank 0 talks to the coupler for all of them (RankRelay).
  FluidBlocks blocks;
  if (const int code = set_up_blocks(opt, mpi, scene, blocks)) return code;
  parallel::CartComm& comm = *blocks.comm;
  FluidSimulation* sim = blocks.sim.get();
  std::unique_ptr<coupled::CoupledBoundary> boundary;
  try {
    boundary = coupled::make_coupled_boundary(*sim);
    boundary->set_block_links(blocks.links.get());
  } catch (const std::exception& e) {
    spdlog::error("{}: cannot set up the fluid solver: {}", opt.scene_name(), e.what());
    return 2;
  }
  if (const int code = prepare_output(opt, comm)) return code;
  std::unique_ptr<parallel::RankWatchdog> watchdog;  // a rank that falls silent ends the run (summary.json says so)
  if (comm.size() > 1)
    watchdog = std::make_unique<parallel::RankWatchdog>(
        parallel::rank_silence_timeout(), [&, name = scene.name](const std::string& message, int silent, int code) {
          app::write_silent_rank_summary(opt.out_dir, name, message, mpi.size(), silent, mpi.rank(), code);
        });
  app::install_interrupt_handlers();

  io::SnapshotSeries series(opt.out_dir, "fluid");  // every rank's (rank 0 publishes the files)
  RunRecord rec;
  for (int d = 0; d < scene.dim; ++d) rec.cells = (d == 0 ? 1.0 : rec.cells) * scene.cells[d];
  const auto fail_alone = [&](int code, const std::string& error) {
    fluid::fail_alone(opt, scene, *sim, comm, rec, code, error);
  };
  double solver_seconds = 0;
  bool first = true;
  FluidRunState restored;
  if (!opt.restart.empty()) {
    try {
      restored = read_fluid_part_over_blocks(opt.restart, *sim, series, comm, boundary.get());
    } catch (const std::exception& e) {
      spdlog::error("--restart {}: {}", opt.restart.string(), e.what());
      return 2;
    }
    rec.start_totals = restored.start_totals;
    solver_seconds = restored.counters.value("flow_solver_seconds", 0.0);
    first = false;
    spdlog::info("restarted from cycle {} at t = {:.9g} s ({})", restored.cycle, restored.time, opt.restart.string());
  }

  coupling::SolverPhases phases;
  for (const auto& ph : scene.phases) {
    phases.names.push_back(ph.name);
    phases.min_pressure.push_back(-ph.eos.pinf);  // a stiffened gas admits p + pinf > 0
  }
  std::unique_ptr<coupling::Client> connection;
  if (root)
    connection = coupling::connect_solver(opt, coupling::Role::Fluid, "fluid_solver", std::move(phases), restored.cycle,
                                          restored.time, comm.size());
  coupling::RankRelay::Share share;
  parallel::TextTiming relayed;  // the relay's broadcasts, for the summary
  if (comm.size() > 1) share = [&](const std::string& text) { return comm.broadcast(text, &relayed); };
  auto link = std::make_unique<coupling::RankRelay>(std::move(connection), share);
  if (!link->connected()) return 5;
  coupling::RankRelay* client = link.get();
  boundary->sample_wall_velocity(client->mode() == coupling::Mode::Robin);
  spdlog::info("{}: {}D, {:.0f} cells, {} phase(s), {} rank(s), coupled through {} ({} conditions)", scene.name,
               scene.dim, rec.cells, scene.num_phases(), comm.size(), opt.coupler, coupling::mode_name(client->mode()));

  // Pipelined cycle: the proposal for the next step comes from t^n, right after the samples, so the coupler
  // can start the solid's next step while this one advances; the step taken may then exceed this state's
  // stable step a little: the largest ratio is reported (max_step_over_stable), a warning above 1.1.
  const bool pipelined = client->scheme() == coupling::Scheme::Pipelined;
  double max_step_over_stable = restored.counters.value("max_step_over_stable", 0.0);
  bool warned = false;
  const auto note_lag = [&](const coupling::Directive& d, double stable) {
    const double ratio = d.dt / stable;
    max_step_over_stable = std::max(max_step_over_stable, ratio);
    if (ratio > 1.1 && !warned) {
      spdlog::warn(
          "cycle {}: the pipelined step {:.4g} s is {:.2f}x the stable step of this state (CFL {:.3g} -> "
          "{:.3g}); coupling.scheme: sequential avoids the lag",
          d.cycle, d.dt, ratio, scene.cfl, ratio * scene.cfl);
      warned = true;
    }
  };
  const auto solver_work = [&](auto&& f) {  // timed into flow_solver_seconds
    const auto t0 = std::chrono::steady_clock::now();
    const double r = f();
    solver_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  // The solid's faces of this cycle as the embedded boundary: a surface its deformation made invalid (not closed,
  // a degenerate face) is a numerical failure of the coupled run (exit 3); malformed data stays a coupling one.
  const auto embedded_boundary = [&](const coupling::Faces& faces, const coupling::Directive& d) {
    try {
      return boundary->receive_faces(faces, d.dt);
    } catch (const std::invalid_argument&) { throw; } catch (const coupling::CouplingError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw app::NumericalError(
          fmt::format("cycle {}: the solid's surface cannot bound the fluid: {}", d.cycle, e.what()));
    }
  };
  const auto cycle = [&](const coupling::Directive& d) {
    const coupling::Faces faces = client->receive_faces();
    if (first) {
      try {
        coupled::check_structure_inside_domain(scene, faces);
      } catch (const std::invalid_argument& e) { throw app::InputError(e.what()); }
    }
    client->send_samples(embedded_boundary(faces, d));
    const double stable_now = pipelined ? solver_work([&] { return sim->stable_dt(); }) : 0.0;
    if (pipelined) client->propose_dt(stable_now);
    boundary->apply_states(client->receive_states());
    if (first) {  // the flow domain is known from the first geometry on
      rec.start_totals = totals_json(scene, totals_over_blocks(*sim, comm));
      first = false;
    }
    if (pipelined && d.dt > 0) note_lag(d, stable_now);
    const double next = solver_work([&] {
      if (d.dt > 0) sim->advance(d.dt);
      return pipelined ? 0.0 : sim->stable_dt();
    });
    if (!pipelined) client->propose_dt(next);
  };
  const auto output = [&](const coupling::Directive&) {
    const std::string segments = boundary->segments_csv();  // this block's rows
    app::as_io("writing a snapshot", [&] { write_snapshot_over_blocks(series, *sim, comm, &segments); });
  };
  const auto checkpoint = [&](const coupling::Directive& d) {
    FluidRunState st{d.cycle,
                     d.time,
                     rec.start_totals,
                     {{"flow_solver_seconds", solver_seconds}, {"max_step_over_stable", max_step_over_stable}}};
    return app::as_io("writing the checkpoint part", [&] {
      return write_fluid_part_over_blocks(d.directory, *sim, series, st, comm, boundary.get());
    });
  };
  const coupling::SolverLoopResult res = coupling::run_solver_loop(*client, *sim, cycle, output, checkpoint);
  rec.status = res.status;
  rec.error = res.error;
  rec.wall = res.wall;
  // A failure of this rank's own ends every rank from here; one that every rank received from the coupler (through
  // rank 0) ends the run together, with one summary.
  if (res.code != 0 && comm.size() > 1 && !link->failed_together())
    fail_alone(res.code, res.error.empty() ? res.status : res.error);
  rec.extra["coupling"] = {{"endpoint", opt.coupler},
                           {"cycles", res.cycles},
                           {"snapshots", res.snapshots},
                           {"checkpoints", res.checkpoints},
                           {"restarted_from", opt.restart.empty() ? nlohmann::json() : nlohmann::json(restored.cycle)},
                           {"flow_solver_seconds", solver_seconds},
                           {"geometry_seconds", boundary->geometry_seconds()},
                           {"scheme", coupling::scheme_name(client->scheme())},
                           {"max_step_over_stable", max_step_over_stable}};
  if (first) rec.start_totals = totals_json(scene, totals_over_blocks(*sim, comm));
  record_over_blocks(rec, scene, *sim, comm);
  if (comm.size() > 1)
    rec.extra["parallel"]["relay"] =
        relay_over_blocks(comm, relayed, blocks.links->texts_timing(), link->codec_seconds());
  if (!root) return 0;
  try {
    write_summary(opt.out_dir, *sim, rec);
  } catch (const std::exception& e) {
    spdlog::error("cannot write summary.json: {}", e.what());
    return res.code ? res.code : 4;
  }
  if (res.code == 0)
    spdlog::info(
        "done: t = {:.6g} in {} cycles, {:.2f} s wall ({:.2f} s flow solver, {:.2f} s geometry), {} "
        "snapshot(s) in {}",
        sim->time(), res.cycles, res.wall, solver_seconds, boundary->geometry_seconds(), series.count(),
        opt.out_dir.string());
  return res.code;
}

}  // namespace cosim::fluid
