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
#include "fluid_solver/app/block_setup.h"
#include "fluid_solver/app/run_summary.h"
#include "fluid_solver/app/runner.h"
#include "fluid_solver/io/fluid_output.h"
#include "fluid_solver/parallel/block_io.h"
#include "fluid_solver/parallel/mesh_split.h"

namespace cosim::fluid {

int run_fluid_blocks(const RunOptions& opt, const parallel::MpiSession& mpi) {
  const bool root = mpi.rank() == 0;
  auto loaded = app::load_scene<FluidScene>(opt, load_fluid_scene);
  if (!loaded) return 2;
  FluidScene scene = std::move(*loaded);
  FluidBlocks blocks;
  if (const int code = set_up_blocks(opt, mpi, scene, blocks)) return code;
  parallel::CartComm* comm = blocks.comm.get();
  FluidSimulation* sim = blocks.sim.get();
  if (const int code = prepare_output(opt, *comm)) return code;
  double cells = 1;
  for (int d = 0; d < scene.dim; ++d) cells *= scene.cells[d];
  const auto& layout = comm->layout().blocks;
  spdlog::info("{}: {}D, {:.0f} cells, {} phase(s), flux {}, {} rank(s) ({} blocks), {} thread(s) per rank", scene.name,
               scene.dim, cells, scene.num_phases(), to_string(scene.flux), comm->size(),
               fmt::join(layout.begin(), layout.begin() + scene.dim, " x "), omp_get_max_threads());

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
  const auto fail_alone = [&](int code, const std::string& error) {
    fluid::fail_alone(opt, scene, *sim, *comm, rec, code, error);
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
  record_over_blocks(rec, scene, *sim, *comm);
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
