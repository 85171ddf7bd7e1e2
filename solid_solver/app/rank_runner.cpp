// The standalone solid run over the ranks of an MPI launcher (mpirun -np N solid_solver ...): every rank reads the
// scene (a Gmsh mesh file only rank 0 reads, and broadcasts: rank_mesh.h) and builds the whole mesh alike, METIS splits
// its elements (mesh/partition.h), and each rank updates its own nodes and the elements around them (mesh/rank_part.h),
// bit for bit as one rank would. One snapshot series, block history and summary, written by rank 0 from the state
// gathered in global order. A failure on one rank (a bad state, an I/O error) ends every rank: that rank writes the
// summary with its message and aborts the run with its exit code, so no rank waits in an exchange for one that stopped;
// a silent rank is found by the rank watchdog.
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>

#include "common/app/rank_failure.h"
#include "common/checkpoint/checkpoint_sets.h"
#include "common/checkpoint/output_resume.h"
#include "common/io/atomic_file.h"
#include "common/parallel/mpi/graph_comm.h"
#include "common/parallel/mpi/rank_watchdog.h"
#include "solid_solver/app/rank_links_mpi.h"
#include "solid_solver/app/rank_mesh.h"
#include "solid_solver/app/rank_record.h"
#include "solid_solver/app/run_summary.h"
#include "solid_solver/app/runner.h"
#include "solid_solver/app/solid_checkpoint.h"
#include "solid_solver/io/block_history.h"
#include "solid_solver/io/solid_output.h"

namespace cosim::solid {

namespace {

struct RestoredRun {
  EnergyBudget start;
  long outputs_done = 0;
};

// SET/solid.h5 of a standalone run: the whole state into `sim` (every rank alike), the start energy and how many
// output times the run had passed. Throws std::runtime_error naming the file and the entry.
RestoredRun restore_run(const std::filesystem::path& set, Simulation& sim, const SolidScene& scene) {
  const checkpoint::PartReader r = checkpoint::open_verified_part(set, kSolidPart, "solid");
  sim.restore_state(r);
  RestoredRun out;
  const std::vector<double> start = r.doubles("run.start_energy", 4);
  out.start = {start[0], start[1], start[2], start[3]};
  const nlohmann::json counters = nlohmann::json::parse(r.text("run.counters"));
  if (!counters.contains("outputs_done"))
    throw std::runtime_error(r.path().string() + ": not a standalone run's part (no outputs_done)");
  out.outputs_done = counters["outputs_done"].get<long>();
  if (sim.time() >= scene.t_end * (1.0 - 1e-14))
    throw std::runtime_error(
        fmt::format("the checkpoint is at t = {:.9g} s, at or after solid.time.end = {:g} s", sim.time(), scene.t_end));
  return out;
}

}  // namespace

int run_solid_ranks(const RunOptions& opt, const parallel::MpiSession& mpi) {
  const bool root = mpi.rank() == 0;
  // One voice for what every rank finds alike (the scene, the set-up); afterwards a rank's own warnings and errors.
  if (!root) spdlog::set_level(spdlog::level::off);
  parallel::GraphComm comm(mpi);
  // A Gmsh mesh on several ranks: read by rank 0 alone and broadcast (rank_mesh.h); one rank reads it itself.
  MeshBroadcast mesh_read;
  const MeshLoader load_mesh = mpi.size() > 1 ? mesh_read_on_rank_zero(comm, mesh_read) : MeshLoader();
  auto loaded =
      app::load_scene<SolidScene>(opt, [&](const std::string& file, const std::vector<std::string>& overrides) {
        return load_solid_scene(file, overrides, load_mesh);
      });
  if (comm.any(!loaded)) {  // alike on every rank (the same scene, rank 0's mesh or its error): every rank ends
    if (!root) spdlog::set_level(spdlog::level::err);
    return 2;
  }
  SolidScene scene = std::move(*loaded);
  set_threads_per_rank(scene, mpi);

  std::unique_ptr<Simulation> sim;
  std::unique_ptr<MpiRankLinks> links;
  long cut_faces = 0;
  std::string setup_error, restart_error;
  int setup_code = 2;
  RestoredRun restored;
  try {  // every rank the same mesh, state and partition
    sim = std::make_unique<Simulation>(scene);
    if (!opt.restart.empty()) {  // every rank reads the whole state of the set
      try {
        restored = restore_run(opt.restart, *sim, scene);
      } catch (const std::exception& e) { restart_error = e.what(); }
    }
    if (mpi.size() > 1) {
      const MeshPartition partition = partition_elements(sim->mesh(), mpi.size());
      cut_faces = partition.cut_faces;
      links = std::make_unique<MpiRankLinks>(comm, make_rank_part(sim->mesh(), partition, mpi.rank()));
      sim->set_rank_links(links.get());
    } else {  // the one-rank time step, untouched; the part only for the summary
      links = std::make_unique<MpiRankLinks>(comm, whole_mesh_part(sim->mesh()));
    }
  } catch (const StateError& e) {
    setup_error = e.what();
    setup_code = 3;
  } catch (const std::exception& e) { setup_error = e.what(); }
  if (!root) spdlog::set_level(spdlog::level::err);
  if (comm.any(!setup_error.empty())) {
    if (!setup_error.empty() && root)
      spdlog::error("{}: cannot set up the solid solver{}: {}", opt.scene_name(),
                    mpi.size() > 1 ? fmt::format(" on {} ranks", mpi.size()) : "", setup_error);
    return setup_code;
  }
  if (comm.any(!restart_error.empty())) {
    if (!restart_error.empty() && root) spdlog::error("--restart {}: {}", opt.restart.string(), restart_error);
    return 2;
  }
  if (root && !app::make_output_directory(opt.out_dir)) parallel::MpiSession::abort_all(4);
  if (root) {  // an earlier run's: a failing rank's summary is then the only one (fail_alone)
    std::error_code ec;
    std::filesystem::remove(opt.out_dir / "summary.json", ec);
  }
  comm.barrier();  // the folder exists before any rank writes into it
  const RankPart& part = links->part();
  spdlog::info("{}: {}D, {} elements, {} nodes, {} block(s), {} rank(s) (METIS, {} cut faces), {} thread(s) per rank",
               scene.name, scene.dim, sim->mesh().num_elements, sim->mesh().num_nodes, scene.blocks.size(), mpi.size(),
               cut_faces, omp_get_max_threads());

  // A rank that falls silent (stopped, hung) ends the run; the rank that notices says so in summary.json.
  const double silence = parallel::rank_silence_timeout();
  parallel::RankWatchdog watchdog(silence, [&, name = scene.name](const std::string& message, int silent, int code) {
    app::write_silent_rank_summary(opt.out_dir, name, message, mpi.size(), silent, mpi.rank(), code);
  });
  app::install_interrupt_handlers();
  std::unique_ptr<io::SnapshotSeries> series;
  std::unique_ptr<BlockHistory> history;
  std::string output_error;
  if (root) {
    try {
      series = std::make_unique<io::SnapshotSeries>(opt.out_dir, "solid");
      if (opt.restart.empty()) {
        history = std::make_unique<BlockHistory>(opt.out_dir);
        if (!opt.checkpoints.empty()) checkpoint::clear(opt.checkpoints);  // an earlier run's sets
      } else {  // the outputs continue where the set was written
        const checkpoint::PartReader r = checkpoint::open_verified_part(opt.restart, kSolidPart, "solid");
        checkpoint::resume_series(r, "solid", *series);
        history = std::make_unique<BlockHistory>(opt.out_dir, &r);
      }
    } catch (const std::exception& e) { output_error = e.what(); }
  }
  if (comm.any(!output_error.empty())) {
    if (root) spdlog::error("{}: {}", opt.restart.empty() ? opt.out_dir.string() : opt.restart.string(), output_error);
    return opt.restart.empty() ? 4 : 2;
  }
  RunRecord rec;
  rec.start = opt.restart.empty() ? energy_over_ranks(*sim, comm) : restored.start;
  // The time loop sees the simulation through this adapter: a block-history row every history_every steps, from
  // the state gathered on rank 0.
  struct WithHistory {
    Simulation& sim;
    BlockHistory* history;
    int every;
    double stable_dt() const { return sim.stable_dt(); }
    std::string limiting_step() const { return sim.limiting_step(); }
    double time() const { return sim.time(); }
    long steps() const { return sim.steps(); }
    void advance(double dt) {
      sim.advance(dt);
      if (every > 0 && sim.steps() % every == 0) {
        sim.gather_state();
        if (history) app::as_io("the block history", [&] { history->record(sim); });
      }
    }
  } stepped{*sim, history.get(), scene.history_every};
  app::DriveOptions drive_opt{scene.output_times,
                              scene.t_end,
                              scene.max_steps,
                              scene.numerics.dt_min,
                              static_cast<double>(sim->mesh().num_elements),
                              "Mzone-cycles/s",
                              opt.quiet || !root};
  // A failure on this rank alone: its summary and message, then every rank ends with its code.
  const auto fail_alone = [&](int code, const std::string& error) {
    rec.status = code == 130 ? "interrupted" : "failed";
    rec.error = fmt::format("{} ({}, {} elements)", error, mpi.describe(), part.owned_elements);
    spdlog::error("{}: {}", mpi.describe(), error);
    if (app::keeps_another_ranks_summary(code, mpi.size(), opt.out_dir)) parallel::MpiSession::abort_all(code);
    rec.extra["parallel"] = {{"ranks", mpi.size()}, {"layout", "metis"}, {"failed_rank", mpi.rank()}};
    rec.end = sim->energy();  // this rank's share only: the others cannot be asked
    try {
      write_summary(opt.out_dir, *sim, rec);
    } catch (const std::exception& e) { spdlog::error("cannot write summary.json: {}", e.what()); }
    parallel::MpiSession::abort_all(code);
  };
  if (!opt.restart.empty()) {
    drive_opt.resumed = true;
    drive_opt.outputs_done = restored.outputs_done;
    spdlog::info("restarted from step {} at t = {:.9g} s ({})", sim->steps(), sim->time(), opt.restart.string());
  }
  // solid.checkpoint: a set of one part (solid.h5, the whole state gathered on rank 0), with its manifest.
  const auto write_checkpoint = [&] {
    sim->gather_state();
    if (!root) return;
    const std::filesystem::path dir = checkpoint::prepare_set(opt.checkpoints, sim->steps());
    const long outputs_done = series->count() > 0 ? static_cast<long>(series->count()) - 1 : 0;
    const std::string file = write_solid_part(
        dir, *sim, *series, *history,
        {sim->steps(), sim->time(), rec.start, {}, false, nlohmann::json{{"outputs_done", outputs_done}}});
    nlohmann::json m = checkpoint::scene_record(opt.scene_file, opt.overrides);
    m["parts"] = {file};
    checkpoint::write_manifest(dir, sim->steps(), sim->time(), m);
    checkpoint::prune(opt.checkpoints, scene.checkpoint.keep);
  };
  const auto after_step = [&](double t_prev) {
    if (!scene.checkpoint.enabled() || !scene.checkpoint.due(sim->steps(), t_prev, sim->time())) return;
    app::as_io("writing a checkpoint", [&] { write_checkpoint(); });
  };
  const app::DriveResult res = app::drive(
      stepped, drive_opt,
      [&] {
        sim->gather_state();
        if (!root) return;
        if (scene.write_snapshots) write_snapshot(*series, *sim);
        history->record(*sim);
      },
      after_step);
  rec.status = res.status;
  rec.error = res.error;
  if (res.code != 0 && mpi.size() > 1) fail_alone(res.code, res.error.empty() ? res.status : res.error);
  rec.wall = comm.max(res.wall);
  rec.end = energy_over_ranks(*sim, comm);
  rec.extra["parallel"] = parallel_record(comm, *sim, part, cut_faces);
  if (mesh_read.used) rec.extra["parallel"]["mesh"] = mesh_broadcast_record(comm, mesh_read);
  if (!root) return 0;
  try {
    write_summary(opt.out_dir, *sim, rec);
  } catch (const std::exception& e) {
    spdlog::error("cannot write summary.json: {}", e.what());
    return res.code ? res.code : 4;
  }
  if (res.code != 0) return res.code;
  const EnergyBudget& e = *rec.end;
  spdlog::info(
      "done: t = {:.6g} in {} steps on {} ranks, {:.2f} s wall, energy balance error {:.3g} (relative), {} "
      "snapshot(s) in {}",
      sim->time(), sim->steps(), mpi.size(), rec.wall,
      rec.start.total() != 0 ? (e.total() - rec.start.total() - e.sources()) / std::abs(rec.start.total()) : 0.0,
      series->count(), opt.out_dir.string());
  return 0;
}

}  // namespace cosim::solid
