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
#include "solid_solver/app/rank_plan.h"
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
  const EnergyBudget e = rec.end ? *rec.end : sim.energy();
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

SolidRun prepare_solid_run(const RunOptions& opt, bool make_output, const MeshLoader& load_mesh) {
  SolidRun r;
  auto loaded = app::load_scene<SolidScene>(opt, [&](const std::string& file, const std::vector<std::string>& ov) {
    return load_solid_scene(file, ov, load_mesh);
  });
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
  if (r.sim && make_output &&
      !app::make_output_directory(opt.out_dir)) {  // only for a run that can start: no empty folders
    r.sim.reset();
    r.exit_code = 4;
  }
  return r;
}

int run_solid(const RunOptions& opt, const parallel::MpiSession& mpi) {
  if (opt.check) {
    // The scene and its mesh as a run sets them up, nothing written; one plan line (rank 0).
    if (mpi.rank() != 0) return 0;
    auto loaded = app::load_scene<SolidScene>(
        opt, [](const std::string& file, const std::vector<std::string>& ov) { return load_solid_scene(file, ov); });
    if (!loaded) return 2;
    try {
      Simulation sim(*loaded);
      const Mesh& m = sim.mesh();
      // The plan line cosim check prints.
      const double dt = sim.stable_dt();
      nlohmann::json facts = {{"max_subcycles", loaded->numerics.max_subcycles}};
      const std::string ranks_line =  // the parts on --ranks N, refused as the run would refuse them
          opt.check_ranks > 1 ? solid_rank_plan(*loaded, m, opt.check_ranks, sim.bytes_per_element(), facts) : "";
      std::cout << fmt::format("solid: {}D, {} elements, {} nodes, {} block(s), state about {}, {}\n", m.dim,
                               m.num_elements, m.num_nodes, loaded->blocks.size(),
                               util::format_bytes(sim.bytes_per_element() * m.num_elements),
                               dt < 1e100 ? fmt::format("first stable step {:.3g} s", dt)
                                          : std::string("rigid bodies only (no step limit of its own)"));
      if (!ranks_line.empty()) std::cout << "solid " << ranks_line << "\n";
      if (opt.plan_facts) {
        if (dt < 1e100) facts["first_step"] = dt;
        app::print_plan_facts(facts);
      }
    } catch (const std::exception& e) {
      spdlog::error("{}: cannot set up the solid solver: {}", opt.scene_name(), e.what());
      return 2;
    }
    return 0;
  }
  if (opt.coupled()) return run_solid_coupled(opt, mpi);
  return run_solid_ranks(opt, mpi);
}

}  // namespace cosim::solid
