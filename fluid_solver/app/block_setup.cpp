#include "fluid_solver/app/block_setup.h"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "common/app/rank_failure.h"
#include "common/app/run_driver.h"
#include "common/app/threads.h"
#include "fluid_solver/parallel/block_io.h"

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

int set_up_blocks(const app::RunOptions& opt, const parallel::MpiSession& mpi, FluidScene& scene, FluidBlocks& out) {
  const bool root = mpi.rank() == 0;
  if (!root) spdlog::set_level(spdlog::level::off);
  try {  // the layout: every rank finds the same
    const parallel::Layout layout = fluid_layout(scene, mpi.size());
    out.comm = std::make_unique<parallel::CartComm>(mpi, layout, periodic_axes(scene), scene.cells);
  } catch (const std::exception& e) {
    spdlog::error("{}: cannot set up the fluid solver: {}", opt.scene_name(), e.what());
    return 2;
  }
  std::string setup_error;  // this rank's block (its memory, ...): the ranks agree before any exchange
  try {
    assign_block(scene, *out.comm);
    scene.threads = threads_per_rank(scene, mpi);
    out.sim = make_simulation(scene);
    out.links = std::make_unique<CartBlockLinks>(*out.comm, scene);
    out.sim->set_block_links(out.links.get());
  } catch (const std::exception& e) { setup_error = e.what(); }
  if (!root) spdlog::set_level(spdlog::level::err);
  const std::string who = mpi.describe().empty() ? "" : mpi.describe() + ": ";
  if (!setup_error.empty())
    spdlog::error("{}{}: cannot set up the fluid solver: {}", who, opt.scene_name(), setup_error);
  if (out.comm->any(!setup_error.empty())) return 2;
  try {  // the embedded bodies' geometry needs the other blocks (they agree on a failure: every rank ends with 2)
    out.sim->start_on_blocks();
  } catch (const std::exception& e) {
    spdlog::error("{}{}: cannot set up the fluid solver: {}", who, opt.scene_name(), e.what());
    return 2;
  }
  return 0;
}

int prepare_output(const app::RunOptions& opt, const parallel::CartComm& comm) {
  const bool root = comm.rank() == 0;
  if (root && !app::make_output_directory(opt.out_dir)) {  // only for a run that can start: no empty folders
    if (comm.size() == 1) return 4;
    parallel::MpiSession::abort_all(4);
  }
  if (root) {  // an earlier run's: a failing rank's summary is then the only one (fail_alone)
    std::error_code ec;
    std::filesystem::remove(opt.out_dir / "summary.json", ec);
  }
  comm.barrier();  // the folder exists, without an earlier summary, before any rank writes into it
  return 0;
}

void fail_alone(const app::RunOptions& opt, const FluidScene& scene, const FluidSimulation& sim,
                const parallel::CartComm& comm, RunRecord& rec, int code, const std::string& error) {
  rec.status = code == 130 ? "interrupted" : "failed";
  rec.error = fmt::format("{} (block of cells [{}, {}) x [{}, {}) x [{}, {}))", error, scene.block.first[0],
                          scene.block.first[0] + scene.block.count[0], scene.block.first[1],
                          scene.block.first[1] + scene.block.count[1], scene.block.first[2],
                          scene.block.first[2] + scene.block.count[2]);
  spdlog::error("rank {} of {}: {}", comm.rank(), comm.size(), rec.error);
  if (app::keeps_another_ranks_summary(code, comm.size(), opt.out_dir)) parallel::MpiSession::abort_all(code);
  rec.extra["parallel"] =
      parallel_record(comm, scene, comm.halo_bytes(), comm.halo_seconds(), comm.halo_wait_seconds());
  rec.extra["parallel"]["failed_rank"] = comm.rank();
  try {
    write_summary(opt.out_dir, sim, rec);  // this rank's totals only: the others cannot be asked
  } catch (const std::exception& e) { spdlog::error("cannot write summary.json: {}", e.what()); }
  parallel::MpiSession::abort_all(code);
}

void record_over_blocks(RunRecord& rec, const FluidScene& scene, const FluidSimulation& sim,
                        const parallel::CartComm& comm) {
  rec.end_totals = totals_over_blocks(sim, comm);
  rec.inflow = inflow_over_blocks(sim, comm);
  if (sim.embedded().active && comm.size() > 1) {
    rec.embedded_mass = embedded_mass_over_blocks(sim, comm);
    rec.embedded_cells = embedded_cells_over_blocks(sim, comm);
    rec.embedded_wall = wall_exchange_over_blocks(sim, comm);
  }
  rec.wall = comm.max(rec.wall);
  std::vector<double> halo{comm.halo_bytes(), comm.sparse_bytes()};
  comm.sum(halo);
  const double halo_s = comm.max(comm.halo_seconds()), wait_s = comm.max(comm.halo_wait_seconds());
  rec.extra["parallel"] = parallel_record(comm, scene, halo[0], halo_s, wait_s);
  if (sim.embedded().active) rec.extra["parallel"]["embedded_exchange_bytes"] = halo[1];
}

nlohmann::json relay_over_blocks(const parallel::CartComm& comm, const parallel::TextTiming& relayed,
                                 const parallel::TextTiming& samples, double codec_s) {
  // Each rank's figures in its slots, summed over the ranks (zeros elsewhere): every rank's, in rank order.
  constexpr std::size_t kFigures = 7;
  const std::size_t ranks = static_cast<std::size_t>(comm.size()), me = static_cast<std::size_t>(comm.rank());
  std::vector<double> all(kFigures * ranks, 0.0);
  const double mine[kFigures] = {relayed.wait_s,     relayed.transfer_s, relayed.bytes, samples.wait_s,
                                 samples.transfer_s, samples.bytes,      codec_s};
  for (std::size_t k = 0; k < kFigures; ++k) all[k * ranks + me] = mine[k];
  comm.sum(all);
  const auto column = [&](std::size_t k) {
    return std::vector<double>(all.begin() + static_cast<std::ptrdiff_t>(k * ranks),
                               all.begin() + static_cast<std::ptrdiff_t>((k + 1) * ranks));
  };
  double relay_s = 0;
  for (std::size_t q = 0; q < ranks; ++q)
    relay_s = std::max(relay_s, all[1 * ranks + q] + all[4 * ranks + q] + all[6 * ranks + q]);
  return {
      {"relay_s", relay_s},
      {"relayed",
       {{"messages", relayed.calls}, {"wait_s", column(0)}, {"transfer_s", column(1)}, {"bytes", column(2)}}},
      {"samples", {{"gathers", samples.calls}, {"wait_s", column(3)}, {"transfer_s", column(4)}, {"bytes", column(5)}}},
      {"codec_s", column(6)}};
}

}  // namespace cosim::fluid
