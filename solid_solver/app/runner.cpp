#include "solid_solver/app/runner.h"

#include <iostream>

#include "common/util/memory.h"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <cstdlib>

#include <atomic>
#include <cmath>
#include <csignal>
#include <memory>

#include "common/app/plan_facts.h"
#include "common/app/version.h"
#include "common/config/config.h"
#include "common/io/atomic_file.h"
#include "common/util/progress.h"
#include "solid_solver/app/run_summary.h"
#include "solid_solver/io/block_history.h"
#include "solid_solver/io/solid_output.h"

namespace cosim::solid {

void write_summary(const std::filesystem::path& dir, const Simulation& sim, const RunRecord& rec) {
  const SolidScene& s = sim.scene();
  nlohmann::json j;
  j["status"] = rec.status;
  if (!rec.error.empty()) j["error"] = rec.error;
  j["scene"] = s.name;
  j["version"] = app::version();
  j["git_commit"] = app::git_commit();
  j["dimension"] = s.dim;
  j["elements"] = sim.mesh().num_elements;
  j["nodes"] = sim.mesh().num_nodes;
  j["final_time"] = sim.time();
  j["t_end"] = s.t_end;
  j["steps"] = sim.steps();
  j["wall_time_s"] = rec.wall;
  const double zc = static_cast<double>(sim.steps()) * sim.mesh().num_elements;
  j["zone_cycles"] = zc;
  j["zone_cycles_per_s"] = rec.wall > 0 ? zc / rec.wall : 0.0;
  j["bytes_per_element"] = sim.bytes_per_element();
  j["threads"] = omp_get_max_threads();
  j["omp_wait_policy"] = std::getenv("OMP_WAIT_POLICY") ? std::getenv("OMP_WAIT_POLICY") : "runtime default";
  const EnergyBudget e = sim.energy();
  const double e0 = rec.start.total();
  j["energy"] = {{"start", energy_json(rec.start)},
                 {"end", energy_json(e)},
                 {"balance_error", e.total() - e0 - e.sources()},
                 {"relative_balance_error", e0 != 0 ? (e.total() - e0 - e.sources()) / std::abs(e0) : 0.0}};
  if (!s.ale.blocks.empty()) {
    const RemapFlux& f = sim.ale_flux();
    j["ale"] = {{"blocks", s.ale.blocks},
                {"inflow_mass", f.mass},
                {"inflow_energy", f.energy},
                {"inflow_momentum", std::vector<double>(f.momentum, f.momentum + s.dim)},
                {"kinetic_to_internal", f.kinetic_to_internal}};
  }
  // Rigid blocks: final centre of mass and velocity (e.g. the piston position of solid_piston_1d).
  for (const auto& rb : sim.rigid_bodies()) {
    const int D = s.dim;
    j["rigid_bodies"].push_back({{"block", s.blocks[rb.block].name},
                                 {"mass", rb.mass},
                                 {"centre_of_mass", std::vector<double>(rb.X, rb.X + D)},
                                 {"velocity", std::vector<double>(rb.V, rb.V + D)}});
  }
  for (const auto& [k, v] : rec.extra.items()) j[k] = v;
  io::write_file_atomically(dir / "summary.json", j.dump(2) + "\n");
}

SolidRun prepare_solid_run(const RunOptions& opt) {
  SolidRun r;
  auto loaded = app::load_scene<SolidScene>(opt, load_solid_scene);
  if (!loaded) return r;
  r.scene = std::move(*loaded);
  if (r.scene.threads > 0) omp_set_num_threads(r.scene.threads);
  try {
    r.sim = std::make_unique<Simulation>(r.scene);
  } catch (const StateError& e) {
    spdlog::error("{}: {}", opt.scene_name(), e.what());
    r.exit_code = 3;
  } catch (const std::exception& e) {
    spdlog::error("{}: cannot set up the solid solver: {}", opt.scene_name(), e.what());
  }
  if (r.sim && !app::make_output_directory(opt.out_dir)) {  // only for a run that can start: no empty folders
    r.sim.reset();
    r.exit_code = 4;
  }
  return r;
}

int run_solid(const RunOptions& opt) {
  if (opt.check) {  // the scene and its mesh as a run sets them up, nothing written
    auto loaded = app::load_scene<SolidScene>(opt, load_solid_scene);
    if (!loaded) return 2;
    try {
      Simulation sim(*loaded);
      const Mesh& m = sim.mesh();
      // The plan line cosim check prints.
      const double dt = sim.stable_dt();
      std::cout << fmt::format("solid: {}D, {} elements, {} nodes, {} block(s), state about {}, {}\n", m.dim,
                               m.num_elements, m.num_nodes, loaded->blocks.size(),
                               util::format_bytes(sim.bytes_per_element() * m.num_elements),
                               dt < 1e100 ? fmt::format("first stable step {:.3g} s", dt)
                                          : std::string("rigid bodies only (no step limit of its own)"));
      if (opt.plan_facts) {
        nlohmann::json facts = {{"max_subcycles", loaded->numerics.max_subcycles}};
        if (dt < 1e100) facts["first_step"] = dt;
        app::print_plan_facts(facts);
      }
    } catch (const std::exception& e) {
      spdlog::error("{}: cannot set up the solid solver: {}", opt.scene_name(), e.what());
      return 2;
    }
    return 0;
  }
  if (opt.coupled()) return run_solid_coupled(opt);
  if (!opt.restart.empty()) {
    spdlog::error(
        "--restart {}: a standalone solid run has no checkpoints (they are written in coupled runs: "
        "coupling.checkpoint)",
        opt.restart.string());
    return 2;
  }
  SolidRun run = prepare_solid_run(opt);
  if (!run.sim) return run.exit_code;
  const SolidScene& scene = run.scene;
  std::unique_ptr<Simulation>& sim = run.sim;
  spdlog::info("{}: {}D, {} elements, {} nodes, {} block(s), {} thread(s)", scene.name, scene.dim,
               sim->mesh().num_elements, sim->mesh().num_nodes, scene.blocks.size(), omp_get_max_threads());

  app::install_interrupt_handlers();
  io::SnapshotSeries series(opt.out_dir, "solid");
  BlockHistory history(opt.out_dir);
  RunRecord rec;
  rec.start = sim->energy();
  // The time loop sees the simulation through this adapter: a block-history row every history_every steps.
  struct WithHistory {
    Simulation& sim;
    BlockHistory& history;
    int every;
    double stable_dt() const { return sim.stable_dt(); }
    std::string limiting_step() const { return sim.limiting_step(); }
    double time() const { return sim.time(); }
    long steps() const { return sim.steps(); }
    void advance(double dt) {
      sim.advance(dt);
      if (every > 0 && sim.steps() % every == 0) app::as_io("the block history", [&] { history.record(sim); });
    }
  } stepped{*sim, history, scene.history_every};
  app::DriveOptions drive_opt{scene.output_times,
                              scene.t_end,
                              scene.max_steps,
                              scene.numerics.dt_min,
                              static_cast<double>(sim->mesh().num_elements),
                              "Mzone-cycles/s",
                              opt.quiet};
  const app::DriveResult res = app::drive(stepped, drive_opt, [&] {
    if (scene.write_snapshots) write_snapshot(series, *sim);
    history.record(*sim);
  });
  rec.status = res.status;
  rec.error = res.error;
  rec.wall = res.wall;
  const int code = res.code;
  try {
    write_summary(opt.out_dir, *sim, rec);
  } catch (const std::exception& e) {
    spdlog::error("cannot write summary.json: {}", e.what());
    return code ? code : 4;
  }
  if (code == 0) {
    const EnergyBudget e = sim->energy();
    spdlog::info(
        "done: t = {:.6g} in {} steps, {:.2f} s wall, {:.3g} Mzone-cycles/s, energy balance error {:.3g} "
        "(relative), {} snapshot(s) in {}",
        sim->time(), sim->steps(), rec.wall,
        rec.wall > 0 ? 1e-6 * sim->steps() * sim->mesh().num_elements / rec.wall : 0.0,
        rec.start.total() != 0 ? (e.total() - rec.start.total() - e.sources()) / std::abs(rec.start.total()) : 0.0,
        series.count(), opt.out_dir.string());
  }
  return code;
}

}  // namespace cosim::solid
