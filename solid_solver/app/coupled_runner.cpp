// The solid's coupled run (paper section 8, step 1; docs/protocol.md): each cycle the solid advances by the
// coupler's step under the interface pressures of the previous cycle, reports its exterior faces, takes
// the new face pressures and proposes its stable step. Snapshots when the coupler asks.
// On several ranks (mpirun -np M solid_solver ..., cosim run --solid-ranks M; docs/parallel.md, "A coupled solid on
// several ranks"): every rank holds the whole mesh (a Gmsh file read by rank 0 alone and broadcast) and updates its own
// nodes (METIS parts, as the standalone run on ranks), rank 0 holds the one connection to the coupler and relays what
// it receives to every rank (RankRelay). The exterior faces' nodes and elements are shared with every rank each cycle,
// so that the faces rank 0 reports and the interface loads every rank applies to its own nodes are those of one rank,
// bit for bit. Rank 0 writes the snapshots, block history, checkpoint part and summary from the state gathered in
// global order.
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "common/app/rank_failure.h"
#include "common/checkpoint/checkpoint_sets.h"
#include "common/coupling/client.h"
#include "common/coupling/rank_relay.h"
#include "common/coupling/scene_hash.h"
#include "common/coupling/solver_loop.h"
#include "common/parallel/mpi/graph_comm.h"
#include "common/parallel/mpi/rank_watchdog.h"
#include "solid_solver/app/rank_links_mpi.h"
#include "solid_solver/app/rank_mesh.h"
#include "solid_solver/app/rank_record.h"
#include "solid_solver/app/run_summary.h"
#include "solid_solver/app/runner.h"
#include "solid_solver/app/solid_checkpoint.h"
#include "solid_solver/coupled/interface_faces.h"
#include "solid_solver/io/block_history.h"
#include "solid_solver/io/solid_output.h"

namespace cosim::solid {

int run_solid_coupled(const RunOptions& opt, const parallel::MpiSession& mpi) {
  const bool root = mpi.rank() == 0, ranks = mpi.size() > 1;
  // One voice for what every rank finds alike (the scene, the set-up); afterwards a rank's own warnings and errors.
  if (!root) spdlog::set_level(spdlog::level::off);
  parallel::GraphComm comm(mpi);
  MeshBroadcast mesh_read;  // a Gmsh mesh on several ranks: read by rank 0 alone and broadcast (rank_mesh.h)
  SolidRun run = prepare_solid_run(opt, root, ranks ? mesh_read_on_rank_zero(comm, mesh_read) : MeshLoader());
  if (comm.any(!run.sim)) {
    if (!root) spdlog::set_level(spdlog::level::err);
    return run.sim ? 2 : run.exit_code;
  }
  const SolidScene& scene = run.scene;
  std::unique_ptr<Simulation>& sim = run.sim;
  set_threads_per_rank(scene, mpi);
  std::optional<io::SnapshotSeries> series;  // rank 0's
  if (root) series.emplace(opt.out_dir, "solid");
  std::optional<checkpoint::PartReader> part;
  SolidRunState restored;
  std::string restart_error, setup_error;
  if (!opt.restart.empty()) {  // every rank restores the whole state; rank 0 continues the outputs
    try {
      part.emplace(checkpoint::open_verified_part(opt.restart, kSolidPart, "solid"));
      restored = read_solid_part(*part, *sim, root ? &*series : nullptr);
    } catch (const std::exception& e) { restart_error = e.what(); }
  }
  if (comm.any(!restart_error.empty())) {
    if (root)
      spdlog::error("--restart {}: {}", opt.restart.string(),
                    restart_error.empty() ? "failed on another rank" : restart_error);
    return 2;
  }
  RunRecord rec;
  rec.start = part ? restored.start : sim->energy();  // the whole mesh's, before the ranks share it
  // Each rank its METIS part (every rank computes the same partition), as the standalone run on ranks.
  std::unique_ptr<MpiRankLinks> links;
  long cut_faces = 0;
  try {
    if (ranks) {
      const MeshPartition partition = partition_elements(sim->mesh(), mpi.size());
      cut_faces = partition.cut_faces;
      links = std::make_unique<MpiRankLinks>(comm, make_rank_part(sim->mesh(), partition, mpi.rank()));
      sim->set_rank_links(links.get());
    } else {
      links = std::make_unique<MpiRankLinks>(comm, whole_mesh_part(sim->mesh()));
    }
  } catch (const std::exception& e) { setup_error = e.what(); }
  if (!root) spdlog::set_level(spdlog::level::err);
  if (comm.any(!setup_error.empty())) {
    if (root)
      spdlog::error("{}: cannot set up the coupled solid on {} ranks: {}", opt.scene_name(), mpi.size(), setup_error);
    return 2;
  }
  if (ranks) {
    if (root) {  // an earlier run's: a failing rank's summary is then the only one (fail_alone)
      std::error_code ec;
      std::filesystem::remove(opt.out_dir / "summary.json", ec);
    }
    comm.barrier();  // the folder exists, without an earlier summary, before any rank writes into it
  }
  std::unique_ptr<parallel::RankWatchdog> watchdog;  // a rank that falls silent ends the run (summary.json says so)
  if (ranks)
    watchdog = std::make_unique<parallel::RankWatchdog>(
        parallel::rank_silence_timeout(), [&, name = scene.name](const std::string& message, int silent, int code) {
          app::write_silent_rank_summary(opt.out_dir, name, message, mpi.size(), silent, mpi.rank(), code);
        });
  app::install_interrupt_handlers();

  std::unique_ptr<coupling::Client> connection;
  if (root)
    connection = coupling::connect_solver(opt, coupling::Role::Solid, "solid_solver", {}, restored.cycle, restored.time,
                                          mpi.size());
  coupling::RankRelay::Share share;
  if (ranks) share = [&](const std::string& text) { return comm.broadcast(text); };
  auto link = std::make_unique<coupling::RankRelay>(std::move(connection), share);
  if (!link->connected()) return 5;
  coupling::RankRelay* client = link.get();
  const InterfaceFaceMap map = make_interface_face_map(sim->boundary_faces());
  spdlog::info("{}: {}D, {} elements, {} interface faces, {} rank(s) ({} cut faces), coupled through {}", scene.name,
               scene.dim, sim->mesh().num_elements, sim->boundary_faces().count, mpi.size(), cut_faces, opt.coupler);

  std::unique_ptr<BlockHistory> history;  // rank 0's
  std::string output_error;
  if (root) {
    try {
      history = std::make_unique<BlockHistory>(opt.out_dir, part ? &*part : nullptr);
    } catch (const std::exception& e) { output_error = e.what(); }
  }
  if (comm.any(!output_error.empty())) {
    if (root) spdlog::error("{}", output_error);
    return part ? 2 : 4;
  }
  long cycles = restored.counters.value("cycles", 0L);
  double solver_seconds = restored.counters.value("solver_seconds", 0.0);
  long substeps = restored.counters.value("solid_steps", 0L);
  coupling::InterfaceStates last = restored.last;  // held over the substeps of the next cycle
  bool apply_velocity = restored.apply_velocity;
  // The coupler's states of a cycle, for the solid's next step (every rank the same states, each applies them to its
  // own nodes).
  const auto apply_states = [&](const coupling::InterfaceStates& st) {
    sim->set_face_pressures(st.face_pressure);
    // Robin: the fluid's impedance enters the solid's own step (no imposed velocity); impedance and
    // characteristic: the nodes of wetted faces take the interface velocity.
    const bool robin = client->mode() == coupling::Mode::Robin;
    if (robin) {
      if (st.face_impedance.size() != st.face_pressure.size())
        throw std::invalid_argument(fmt::format("InterfaceStates.face_impedance: {} values for {} faces (mode robin)",
                                                st.face_impedance.size(), st.count));
      sim->set_face_impedances(st.face_impedance);
    }
    apply_velocity =
        !robin && client->mode() != coupling::Mode::Standard && st.face_wetted.size() == st.face_pressure.size();
    if (apply_velocity) sim->set_face_normal_velocities(st.face_normal_velocity, st.face_wetted);
    last = st;
  };
  if (part) {  // the set's cycle ended with these states: set again on the restored faces (at t^n, as then)
    sim->boundary_faces();
    apply_states(restored.last);
    part.reset();
    spdlog::info("restarted from cycle {} at t = {:.9g} s ({})", restored.cycle, restored.time, opt.restart.string());
  }
  // Every rank the whole state on rank 0 (a collective call), then rank 0 records it.
  const auto record_history = [&] {
    sim->gather_state();
    if (root) app::as_io("the block history", [&] { history->record(*sim); });
  };
  const auto cycle = [&](const coupling::Directive& d) {
    const auto t0 = std::chrono::steady_clock::now();
    // With the face pressures of the previous cycle; in substeps when the coupled step is longer than the
    // solid's stable step (numerics.max_subcycles > 1), the interface pressure and velocity held over them.
    if (d.dt > 0) {
      const int n = std::max(1, static_cast<int>(std::ceil(d.dt / sim->stable_dt() - 1e-9)));
      if (n > scene.numerics.max_subcycles)
        throw app::NumericalError(
            fmt::format("the coupled step {:.4g} s needs {} solid substeps, more than "
                        "solid.numerics.max_subcycles = {}",
                        d.dt, n, scene.numerics.max_subcycles));
      for (int k = 0; k < n; ++k) {
        if (k > 0 && apply_velocity) sim->set_face_normal_velocities(last.face_normal_velocity, last.face_wetted);
        sim->advance(d.dt / n);
      }
      substeps += n;
    }
    sim->share_boundary_state();
    const BoundaryFaces& bf = sim->boundary_faces();
    const coupling::Faces faces = root ? interface_faces(bf, map, sim->state()) : coupling::Faces{};
    solver_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    client->send_faces(faces);
    // The proposal does not depend on the states: sent at once, so that in the pipelined cycle the coupler
    // can decide the next step as soon as the fluid has proposed. The stable step is the minimum over the ranks.
    client->propose_dt(scene.numerics.max_subcycles * sim->stable_dt());
    const coupling::InterfaceStates st = client->receive_states();
    if (st.count != bf.count)
      throw std::invalid_argument(
          fmt::format("InterfaceStates.count = {} but the solid has {} interface faces", st.count, bf.count));
    if (static_cast<int>(st.face_pressure.size()) != st.count)
      throw std::invalid_argument(
          fmt::format("InterfaceStates.face_pressure: {} values for {} faces", st.face_pressure.size(), st.count));
    apply_states(st);
    if (scene.history_every > 0 && ++cycles % scene.history_every == 0) record_history();
  };
  const auto output = [&](const coupling::Directive&) {
    sim->gather_state();
    if (!root) return;
    app::as_io("writing a snapshot", [&] {
      if (scene.write_snapshots) write_snapshot(*series, *sim);
      history->record(*sim);
    });
  };
  const auto checkpoint = [&](const coupling::Directive& d) {
    sim->gather_state();
    if (!root) return std::string(kSolidPart);
    SolidRunState st{
        d.cycle, d.time,         rec.start,
        last,    apply_velocity, {{"cycles", cycles}, {"solver_seconds", solver_seconds}, {"solid_steps", substeps}}};
    return app::as_io("writing the checkpoint part",
                      [&] { return write_solid_part(d.directory, *sim, *series, *history, st); });
  };
  const coupling::SolverLoopResult res = coupling::run_solver_loop(*client, *sim, cycle, output, checkpoint);
  rec.status = res.status;
  rec.error = res.error;
  rec.wall = res.wall;
  rec.extra["coupling"] = {{"endpoint", opt.coupler},
                           {"cycles", res.cycles},
                           {"snapshots", res.snapshots},
                           {"checkpoints", res.checkpoints},
                           {"restarted_from", opt.restart.empty() ? nlohmann::json() : nlohmann::json(restored.cycle)},
                           {"solver_seconds", solver_seconds},
                           {"solid_steps", substeps}};
  if (ranks) {
    // A failure of this rank's own ends every rank from here (the others may wait in an exchange); one that every
    // rank received from the coupler (through rank 0) ends the ranks together, with one summary.
    if (res.code != 0 && !link->failed_together()) {
      rec.status = res.code == 130 ? "interrupted" : "failed";
      rec.error = fmt::format("{} ({}, {} elements)", res.error.empty() ? res.status : res.error, mpi.describe(),
                              links->part().owned_elements);
      spdlog::error("{}", rec.error);
      if (app::keeps_another_ranks_summary(res.code, mpi.size(), opt.out_dir))
        parallel::MpiSession::abort_all(res.code);
      rec.extra["parallel"] = {{"ranks", mpi.size()}, {"layout", "metis"}, {"failed_rank", mpi.rank()}};
      rec.end = sim->energy();  // this rank's share only: the others cannot be asked
      try {
        write_summary(opt.out_dir, *sim, rec);
      } catch (const std::exception& e) { spdlog::error("cannot write summary.json: {}", e.what()); }
      parallel::MpiSession::abort_all(res.code);
    }
    rec.wall = comm.max(res.wall);
    rec.end = energy_over_ranks(*sim, comm);
    rec.extra["parallel"] = parallel_record(comm, *sim, links->part(), cut_faces);
    if (mesh_read.used) rec.extra["parallel"]["mesh"] = mesh_broadcast_record(comm, mesh_read);
  }
  if (!root) return res.code;
  try {
    write_summary(opt.out_dir, *sim, rec);
  } catch (const std::exception& e) {
    spdlog::error("cannot write summary.json: {}", e.what());
    return res.code ? res.code : 4;
  }
  if (res.code == 0)
    spdlog::info(
        "done: t = {:.6g} in {} cycles on {} rank(s), {:.2f} s wall ({:.2f} s solid solver), {} snapshot(s) in {}",
        sim->time(), res.cycles, mpi.size(), rec.wall, solver_seconds, series->count(), opt.out_dir.string());
  return res.code;
}

}  // namespace cosim::solid
