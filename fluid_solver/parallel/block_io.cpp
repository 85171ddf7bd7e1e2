#include "fluid_solver/parallel/block_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/checkpoint/output_resume.h"
#include "common/checkpoint/part_file.h"
#include "common/io/atomic_file.h"
#include "fluid_solver/core/fluid_state_entries.h"
#include "fluid_solver/io/fluid_output.h"

namespace cosim::fluid {

namespace {

// Per phase mass, momentum[3], energy, flattened, summed over the ranks (in rank order: the last bits may differ
// from one rank's sum over the same cells).
std::vector<PhaseTotals> summed(std::vector<PhaseTotals> t, const parallel::CartComm& comm) {
  std::vector<double> flat;
  for (const PhaseTotals& p : t) {
    flat.push_back(p.mass);
    flat.insert(flat.end(), p.momentum.begin(), p.momentum.end());
    flat.push_back(p.energy);
  }
  comm.sum(flat);
  for (std::size_t k = 0; k < t.size(); ++k) {
    t[k].mass = flat[5 * k];
    for (int d = 0; d < 3; ++d) t[k].momentum[d] = flat[5 * k + 1 + d];
    t[k].energy = flat[5 * k + 4];
  }
  return t;
}

}  // namespace

std::string merge_segment_rows(const std::vector<std::string>& parts) {
  std::string header;
  struct Row {
    std::array<long, 3> kji;
    std::string_view text;
  };
  std::vector<Row> rows;
  for (const std::string& part : parts) {
    std::size_t at = part.find('\n');
    if (at == std::string::npos) continue;
    if (header.empty()) header = part.substr(0, at + 1);
    for (++at; at < part.size();) {
      const std::size_t end = std::min(part.find('\n', at), part.size() - 1) + 1;
      const std::string_view line(part.data() + at, end - at);
      long ijk[3] = {0, 0, 0};
      std::size_t pos = 0;
      for (long& v : ijk) {  // the first three columns: i, j, k
        const std::size_t comma = line.find(',', pos);
        v = std::stol(std::string(line.substr(pos, comma - pos)));
        pos = comma + 1;
      }
      rows.push_back({{ijk[2], ijk[1], ijk[0]}, line});
      at = end;
    }
  }
  // By cell in the mesh's order; a cell's rows come from one block, in its order (stable).
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.kji < b.kji; });
  std::string out = header;
  for (const Row& r : rows) out += r.text;
  return out;
}

std::vector<EmbeddedMassAccount> embedded_mass_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm) {
  std::vector<EmbeddedMassAccount> acc = sim.embedded_mass_account();
  std::vector<double> flat;
  for (const auto& a : acc) flat.insert(flat.end(), {a.walls, a.cells});
  comm.sum(flat);
  for (std::size_t k = 0; k < acc.size(); ++k) acc[k] = {flat[2 * k], flat[2 * k + 1]};
  return acc;
}

double embedded_cells_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm) {
  std::vector<double> n{static_cast<double>(sim.embedded().own_ghosts)};
  comm.sum(n);
  return n[0];
}

std::vector<PhaseTotals> totals_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm) {
  return summed(sim.totals(), comm);
}

std::vector<PhaseTotals> inflow_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm) {
  return summed(sim.boundary_inflow(), comm);
}

std::vector<PhaseTotals> wall_exchange_over_blocks(const FluidSimulation& sim, const parallel::CartComm& comm) {
  return summed(sim.embedded_wall_exchange(), comm);
}

void write_snapshot_over_blocks(io::SnapshotSeries& series, const FluidSimulation& sim, const parallel::CartComm& comm,
                                const std::string* segments_of_block) {
  if (comm.size() == 1)  // with the embedded interface segments
    return segments_of_block ? write_snapshot(series, sim, *segments_of_block) : write_snapshot(series, sim);
  const FluidScene& s = sim.scene();
  const SnapshotFields fields(sim);
  const io::UniformGrid g = snapshot_grid(s);
  io::GridPart part;
  for (int d = 0; d < 3; ++d) {
    part.lower[d] = comm.block().lower[d];
    part.upper[d] = comm.block().upper[d];
  }
  const std::size_t index = series.count();
  const std::unique_ptr<io::CollectiveWrite> together = comm.collective_write();
  const std::filesystem::path h5 = series.write_part(sim.time(), sim.steps(), g, part, fields.views, *together);
  if (index == 0 && comm.rank() == 0) io::remove_numbered_files(h5.parent_path(), "fluid_interface_", ".csv");
  const std::string segments =
      segments_of_block ? *segments_of_block : sim.interface_segments_csv();  // this block's cells' rows
  if (!comm.any(!segments.empty())) return;
  const std::vector<std::string> parts = comm.gather_text(segments);
  if (comm.rank() == 0)
    io::write_file_atomically(h5.parent_path() / fmt::format("fluid_interface_{:06d}.csv", index),
                              merge_segment_rows(parts));
}

namespace {
// This rank's cells within the mesh.
CellRange block_range(const parallel::CartComm& comm) {
  const parallel::Block& b = comm.block();
  return CellRange::of(comm.cells(), b.lower,
                       {b.upper[0] - b.lower[0], b.upper[1] - b.lower[1], b.upper[2] - b.lower[2]});
}
}  // namespace

std::string write_fluid_part_over_blocks(const std::filesystem::path& dir, const FluidSimulation& sim,
                                         const io::SnapshotSeries& series, const FluidRunState& run,
                                         const parallel::CartComm& comm, const coupled::CoupledBoundary* boundary) {
  if (comm.size() == 1) return write_fluid_part(dir, sim, series, run, boundary);
  // Every rank writes its block of the mesh's cells into one file (collective HDF5; no rank holds another's cells);
  // the accounts are sums over the blocks; the rest is alike on every rank.
  std::vector<double> accounts = sim.account_values();
  comm.sum(accounts);
  const std::unique_ptr<io::CollectiveWrite> together = comm.collective_write();
  checkpoint::PartWriter w(dir / kFluidPart, "fluid", *together);
  w.put_integer("cycle", run.cycle);
  w.put_scalar("time", run.time);
  const auto phases = static_cast<std::size_t>(sim.scene().num_phases());
  write_fluid_state(w,
                    {sim.conserved_cells(), std::move(accounts), sim.time(), sim.steps(), sim.conserved_vars(),
                     sim.body_state(), block_range(comm)},
                    2 * phases, sim.embedded_wall_exchange().empty() ? 0 : phases * (2 + sim.scene().dim));
  // A conservative boundary's wall pressures, alike on every block (EmbeddedBodiesRun), as one rank writes them.
  if (const std::vector<double> p = sim.embedded_wall_pressure(); !p.empty()) w.put("fluid.embedded_wall_pressure", p);
  if (boundary) boundary->save(w);
  checkpoint::put_series(w, "fluid", series);
  w.put_text("run.start_totals", run.start_totals.dump());
  w.put_text("run.counters", run.counters.dump());
  w.commit();
  return kFluidPart;
}

FluidRunState read_fluid_part_over_blocks(const std::filesystem::path& set, FluidSimulation& sim,
                                          io::SnapshotSeries& series, const parallel::CartComm& comm,
                                          coupled::CoupledBoundary* boundary) {
  if (comm.size() == 1) return read_fluid_part(set, sim, series, boundary);
  // Rank 0 checks the part against its set's manifest and reads what every rank shares; what it found (or why it
  // failed) reaches every rank. Then each rank reads its own block of the cells.
  nlohmann::json head;
  if (comm.rank() == 0) {
    try {
      const checkpoint::PartReader r = checkpoint::open_verified_part(set, kFluidPart, "fluid");
      head = {{"cycle", r.integer("cycle")},
              {"run_time", r.scalar("time")},
              {"start_totals", r.text("run.start_totals")},
              {"counters", r.text("run.counters")}};
      checkpoint::resume_series(r, "fluid", series);
      io::remove_numbered_files(series.xdmf_path().parent_path(), "fluid_interface_", ".csv", series.count());
      head["series"] = series.entries();
    } catch (const std::exception& e) { head = {{"error", e.what()}}; }
  }
  head = nlohmann::json::parse(comm.broadcast(head.dump()));
  if (head.contains("error")) throw std::runtime_error(head["error"].get<std::string>());
  if (comm.rank() != 0) series.follow(head["series"].get<std::vector<std::string>>());
  FluidStateEntries e;
  std::string error;
  std::unique_ptr<checkpoint::PartReader> r;
  try {
    r = std::make_unique<checkpoint::PartReader>(set / kFluidPart, "fluid");
    e = read_fluid_state(*r, sim.conserved_vars(), block_range(comm), sim.body_state().size());
    if (!sim.embedded_wall_pressure().empty() && r->has("fluid.embedded_wall_pressure"))
      sim.set_embedded_wall_pressure(r->doubles("fluid.embedded_wall_pressure", sim.embedded_wall_pressure().size()));
  } catch (const std::exception& x) { error = x.what(); }
  if (comm.any(!error.empty()))
    throw std::runtime_error(
        error.empty() ? fmt::format("another rank could not read its block of {}", (set / kFluidPart).string())
                      : fmt::format("rank {}: {}", comm.rank(), error));
  sim.set_conserved_cells(e.conserved);
  // The accounts are sums over the blocks: rank 0 carries the global sums on, the others start from zero.
  if (comm.rank() != 0) std::fill(e.accounts.begin(), e.accounts.end(), 0.0);
  sim.restore_progress(e.time, e.steps, e.accounts);
  // The bodies where the set left them, cut anew with the restored state (every block together).
  if (!e.body_vertices.empty()) sim.set_body_state(e.body_vertices);
  if (boundary) boundary->restore(*r);  // the set's embedded boundary, cut by every block together
  FluidRunState run;
  run.cycle = head["cycle"].get<long>();
  run.time = head["run_time"].get<double>();
  run.start_totals = nlohmann::json::parse(head["start_totals"].get<std::string>());
  run.counters = nlohmann::json::parse(head["counters"].get<std::string>());
  return run;
}

}  // namespace cosim::fluid
