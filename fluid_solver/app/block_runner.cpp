// The standalone fluid run over the blocks of a split mesh: one block per rank (one rank without a launcher), the
// ghost layers exchanged between them, one snapshot series, summary and checkpoint sets of the whole mesh.
// A failure on one rank (a bad state, an I/O error) ends every rank: that rank writes the summary with its message
// and aborts the run with its exit code, so no rank waits in an exchange for one that stopped.
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdlib>

#include "common/app/rank_failure.h"
#include "common/app/threads.h"
#include "common/checkpoint/checkpoint_sets.h"
#include "common/config/config.h"
#include "common/io/atomic_file.h"
#include "common/parallel/mpi/rank_watchdog.h"
#include "fluid_solver/app/run_summary.h"
#include "fluid_solver/app/runner.h"
#include "fluid_solver/io/fluid_output.h"
#include "fluid_solver/parallel/block_io.h"
#include "fluid_solver/parallel/mesh_split.h"

namespace cosim::fluid {

namespace {

// Threads per rank when neither the scene nor --threads chose: the cores this rank may use shared by the ranks on
// its node, and no more than its rows of cells keep busy (app::threads_for).
int threads_per_rank(const FluidScene& scene, const parallel::MpiSession& mpi) {
  if (scene.threads > 0) return scene.threads;
  const int cores = std::max(1, omp_get_num_procs() / std::max(1, mpi.ranks_on_this_node()));
  const long rows = static_cast<long>(scene.block.count[1]) * scene.block.count[2];
  return std::max(1, std::min(cores, app::threads_for(rows, 16)));
}

// halo: the bytes every rank sent and the most seconds a rank spent in the exchanges, waiting included, and of it
// waiting for the neighbours' messages (their latency and the ranks' imbalance).
nlohmann::json parallel_record(const parallel::CartComm& comm, const FluidScene& scene, double halo_bytes,
                               double halo_seconds, double halo_wait_seconds) {
  const auto& b = comm.layout().blocks;
  return {{"ranks", comm.size()},
          {"layout", std::vector<int>(b.begin(), b.begin() + scene.dim)},
          {"threads_per_rank", omp_get_max_threads()},
          {"halo_bytes", halo_bytes},
          {"halo_seconds", halo_seconds},
          {"halo_wait_seconds", halo_wait_seconds}};
}

}  // namespace

int run_fluid_blocks(const RunOptions& opt, const parallel::MpiSession& mpi) {
  const bool root = mpi.rank() == 0;
  // One voice for what every rank finds alike (the scene, the set-up); afterwards a rank's own warnings and errors.
  if (!root) spdlog::set_level(spdlog::level::off);
  auto loaded = app::load_scene<FluidScene>(opt, load_fluid_scene);
  if (!loaded) return 2;
  FluidScene scene = std::move(*loaded);

  std::unique_ptr<parallel::CartComm> comm;
  std::unique_ptr<CartBlockLinks> links;
  std::unique_ptr<FluidSimulation> sim;
  try {  // the layout: every rank finds the same
    const parallel::Layout layout = fluid_layout(scene, mpi.size());
    comm = std::make_unique<parallel::CartComm>(mpi, layout, periodic_axes(scene), scene.cells);
  } catch (const std::exception& e) {
    spdlog::error("{}: cannot set up the fluid solver: {}", opt.scene_name(), e.what());
    return 2;
  }
  std::string setup_error;  // this rank's block (its memory, ...): the ranks agree before any exchange
  try {
    assign_block(scene, *comm);
    scene.threads = threads_per_rank(scene, mpi);
    sim = make_simulation(scene);
    links = std::make_unique<CartBlockLinks>(*comm, scene);
    sim->set_block_links(links.get());
  } catch (const std::exception& e) { setup_error = e.what(); }
  if (!root) spdlog::set_level(spdlog::level::err);
  if (!setup_error.empty())
    spdlog::error("{}{}: cannot set up the fluid solver: {}", mpi.describe().empty() ? "" : mpi.describe() + ": ",
                  opt.scene_name(), setup_error);
  if (comm->any(!setup_error.empty())) return 2;
  try {  // the embedded bodies' geometry needs the other blocks (they agree on a failure: every rank ends with 2)
    sim->start_on_blocks();
  } catch (const std::exception& e) {
    spdlog::error("{}{}: cannot set up the fluid solver: {}", mpi.describe().empty() ? "" : mpi.describe() + ": ",
                  opt.scene_name(), e.what());
    return 2;
  }
  if (root && !app::make_output_directory(opt.out_dir)) {  // only for a run that can start: no empty folders
    if (comm->size() == 1) return 4;
    parallel::MpiSession::abort_all(4);
  }
  if (root) {  // an earlier run's: a failing rank's summary is then the only one (fail_alone)
    std::error_code ec;
    std::filesystem::remove(opt.out_dir / "summary.json", ec);
  }
  comm->barrier();  // the folder exists, without an earlier summary, before any rank writes into it
  double cells = 1;
  for (int d = 0; d < scene.dim; ++d) cells *= scene.cells[d];
  const auto& blocks = comm->layout().blocks;
  spdlog::info("{}: {}D, {:.0f} cells, {} phase(s), flux {}, {} rank(s) ({} blocks), {} thread(s) per rank", scene.name,
               scene.dim, cells, scene.num_phases(), to_string(scene.flux), comm->size(),
               fmt::join(blocks.begin(), blocks.begin() + scene.dim, " x "), omp_get_max_threads());

  // A rank that falls silent (stopped, hung) ends the run; the rank that notices says so in summary.json.
  const double silence = parallel::rank_silence_timeout();
  parallel::RankWatchdog watchdog(silence, [&, name = scene.name](const std::string& message, int silent, int code) {
    app::write_silent_rank_summary(opt.out_dir, name, message, mpi.size(), silent, mpi.rank(), code);
  });
  app::install_interrupt_handlers();
  io::SnapshotSeries series(opt.out_dir, "fluid");  // every rank's (rank 0 publishes the files)
  RunRecord rec;
  rec.cells = cells;
  app::DriveOptions drive_opt{scene.output_times, scene.t_end,       scene.max_steps, 0.0, cells,
                              "Mcell-updates/s",  opt.quiet || !root};
  // A failure on this rank alone: its summary and message, then every rank ends with its code.
  const auto fail_alone = [&](int code, const std::string& error) {
    rec.status = code == 130 ? "interrupted" : "failed";
    rec.error = fmt::format("{} (block of cells [{}, {}) x [{}, {}) x [{}, {}))", error, scene.block.first[0],
                            scene.block.first[0] + scene.block.count[0], scene.block.first[1],
                            scene.block.first[1] + scene.block.count[1], scene.block.first[2],
                            scene.block.first[2] + scene.block.count[2]);
    spdlog::error("{}: {}", mpi.describe(), rec.error);
    if (app::keeps_another_ranks_summary(code, comm->size(), opt.out_dir)) parallel::MpiSession::abort_all(code);
    rec.extra["parallel"] =
        parallel_record(*comm, scene, comm->halo_bytes(), comm->halo_seconds(), comm->halo_wait_seconds());
    rec.extra["parallel"]["failed_rank"] = comm->rank();
    try {
      write_summary(opt.out_dir, *sim, rec);  // this rank's totals only: the others cannot be asked
    } catch (const std::exception& e) { spdlog::error("cannot write summary.json: {}", e.what()); }
    parallel::MpiSession::abort_all(code);
  };
  if (!opt.restart.empty()) {
    try {
      const FluidRunState restored = read_fluid_part_over_blocks(opt.restart, *sim, series, *comm);
      rec.start_totals = restored.start_totals;
    } catch (const std::exception& e) {
      spdlog::error("--restart {}: {}", opt.restart.string(), e.what());
      return 2;
    }
    if (sim->time() >= scene.t_end * (1.0 - 1e-14)) {
      spdlog::error("--restart {}: the checkpoint is at t = {:.9g} s, at or after fluid.time.end = {:g} s",
                    opt.restart.string(), sim->time(), scene.t_end);
      return 2;
    }
    drive_opt.resumed = true;
    drive_opt.outputs_done = series.count() > 0 ? series.count() - 1 : 0;
    spdlog::info("restarted from step {} at t = {:.9g} s ({})", sim->steps(), sim->time(), opt.restart.string());
  } else {
    rec.start_totals = totals_json(scene, totals_over_blocks(*sim, *comm));
    if (root && !opt.checkpoints.empty()) checkpoint::clear(opt.checkpoints);  // an earlier run's sets
  }
  // fluid.checkpoint: a set of one part (fluid.h5, the whole mesh, written by every rank), complete with its manifest.
  const auto write_checkpoint = [&] {
    std::filesystem::path dir;
    if (root) dir = checkpoint::prepare_set(opt.checkpoints, sim->steps());
    dir = comm->broadcast(dir.string());  // the set's folder exists before the ranks create its part together
    const std::string part = write_fluid_part_over_blocks(
        dir, *sim, series, {sim->steps(), sim->time(), rec.start_totals, nlohmann::json::object()}, *comm);
    if (!root) return;
    nlohmann::json m = checkpoint::scene_record(opt.scene_file, opt.overrides);
    m["parts"] = {part};
    checkpoint::write_manifest(dir, sim->steps(), sim->time(), m);
    checkpoint::prune(opt.checkpoints, scene.checkpoint.keep);
  };
  double output_seconds = 0;
  const auto timed = [&](auto&& write) {
    const auto t0 = std::chrono::steady_clock::now();
    write();
    output_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const auto after_step = [&](double t_prev) {
    if (!scene.checkpoint.enabled() || !scene.checkpoint.due(sim->steps(), t_prev, sim->time())) return;
    timed([&] { app::as_io("writing a checkpoint", [&] { write_checkpoint(); }); });
  };
  const app::DriveResult res = app::drive(
      *sim, drive_opt, [&] { timed([&] { write_snapshot_over_blocks(series, *sim, *comm); }); }, after_step);
  rec.status = res.status;
  rec.error = res.error;
  rec.wall = res.wall;
  if (res.code != 0 && comm->size() > 1) fail_alone(res.code, res.error.empty() ? res.status : res.error);
  rec.end_totals = totals_over_blocks(*sim, *comm);
  rec.inflow = inflow_over_blocks(*sim, *comm);
  if (sim->embedded().active && comm->size() > 1) {
    rec.embedded_mass = embedded_mass_over_blocks(*sim, *comm);
    rec.embedded_cells = embedded_cells_over_blocks(*sim, *comm);
    rec.embedded_wall = wall_exchange_over_blocks(*sim, *comm);
  }
  rec.wall = comm->max(rec.wall);
  std::vector<double> halo{comm->halo_bytes(), comm->sparse_bytes()};
  comm->sum(halo);
  const double halo_s = comm->max(comm->halo_seconds()), wait_s = comm->max(comm->halo_wait_seconds());
  rec.extra["parallel"] = parallel_record(*comm, scene, halo[0], halo_s, wait_s);
  if (!scene.embedded.bodies.empty()) rec.extra["parallel"]["embedded_exchange_bytes"] = halo[1];
  rec.extra["output_seconds"] = comm->max(output_seconds);  // snapshots and checkpoints, within wall_time_s
  if (!root) return 0;
  try {
    write_summary(opt.out_dir, *sim, rec);
  } catch (const std::exception& e) {
    spdlog::error("cannot write summary.json: {}", e.what());
    return res.code ? res.code : 4;
  }
  if (res.code != 0) return res.code;
  spdlog::info("done: t = {:.6g} in {} steps, {:.2f} s wall, {} snapshot(s) in {}", sim->time(), sim->steps(), rec.wall,
               series.count(), opt.out_dir.string());
  return 0;
}

}  // namespace cosim::fluid
