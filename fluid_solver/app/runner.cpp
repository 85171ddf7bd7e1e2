#include "fluid_solver/app/runner.h"

#include <iostream>

#include "common/util/memory.h"
#include "fluid_solver/core/memory_estimate.h"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <cmath>
#include <cstdlib>

#include "common/app/plan_facts.h"
#include "common/app/scene_kind.h"
#include "common/app/version.h"
#include "common/checkpoint/checkpoint_sets.h"
#include "common/config/config.h"
#include "common/io/atomic_file.h"
#include "common/util/progress.h"
#include "fluid_solver/app/fluid_checkpoint.h"
#include "fluid_solver/app/run_summary.h"
#include "fluid_solver/io/fluid_output.h"
#include "fluid_solver/parallel/rank_plan.h"

namespace cosim::fluid {

void write_summary(const std::filesystem::path& dir, const FluidSimulation& sim, const RunRecord& rec) {
  const FluidScene& s = sim.scene();
  nlohmann::json j;
  j["status"] = rec.status;
  if (!rec.error.empty()) j["error"] = rec.error;
  j["scene"] = s.name;
  j["version"] = app::version();
  j["git_commit"] = app::git_commit();
  j["dimension"] = s.dim;
  j["cells"] = std::vector<int>(s.cells.begin(), s.cells.begin() + s.dim);
  j["phases"] = s.num_phases();
  j["flux"] = to_string(s.flux);
  j["final_time"] = sim.time();
  j["t_end"] = s.t_end;
  j["steps"] = sim.steps();
  j["wall_time_s"] = rec.wall;
  const double cells = rec.cells > 0 ? rec.cells : static_cast<double>(sim.interior_cells());
  const double updates = static_cast<double>(sim.steps()) * cells;
  j["cell_updates"] = updates;
  j["cell_updates_per_s"] = rec.wall > 0 ? updates / rec.wall : 0.0;
  j["state_bytes_per_cell"] =
      static_cast<double>(sim.state_bytes()) / static_cast<double>(sim.interior_cells());  // a rank's
  j["threads"] = omp_get_max_threads();
  j["omp_wait_policy"] = std::getenv("OMP_WAIT_POLICY") ? std::getenv("OMP_WAIT_POLICY") : "runtime default";
  const nlohmann::json end_totals = totals_json(s, rec.end_totals ? *rec.end_totals : sim.totals());
  const std::vector<PhaseTotals> inflow = rec.inflow ? *rec.inflow : sim.boundary_inflow();
  // Per phase: end - start of the flow cells' totals, less what entered through the domain boundary when asked.
  const auto change = [&](bool less_inflow) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t k = 0; k < end_totals.size(); ++k) {
      const auto &a = rec.start_totals[k], &b = end_totals[k];
      const PhaseTotals in = less_inflow && k < inflow.size() ? inflow[k] : PhaseTotals{};
      nlohmann::json mom = nlohmann::json::array();
      for (int d = 0; d < 3; ++d)
        mom.push_back(b["momentum"][d].get<double>() - a["momentum"][d].get<double>() - in.momentum[d]);
      out.push_back({{"phase", b["phase"]},
                     {"mass", b["mass"].get<double>() - a["mass"].get<double>() - in.mass},
                     {"momentum", mom},
                     {"energy", b["energy"].get<double>() - a["energy"].get<double>() - in.energy}});
    }
    return out;
  };
  // created: what the scheme itself made (round-off without bodies).
  j["totals"] = {{"start", rec.start_totals},
                 {"end", end_totals},
                 {"boundary_inflow", totals_json(s, inflow)},
                 {"created", change(true)}};
  if (sim.embedded().active) {
    // The embedded boundary is not conservative: what the flow cells gained or lost. In a closed or
    // periodic domain this is exactly what crossed the moving boundary (cells covered or uncovered
    // by the body, and the ghost-cell wall treatment).
    // Each phase's mass account: what the walls pushed through the grid faces and the cells the body covered or
    // uncovered; `unaccounted` (created less both) is the scheme's round-off.
    const std::vector<EmbeddedMassAccount> acc = rec.embedded_mass ? *rec.embedded_mass : sim.embedded_mass_account();
    const nlohmann::json& created = j["totals"]["created"];
    nlohmann::json mass = nlohmann::json::array();
    for (std::size_t k = 0; k < acc.size() && k < created.size(); ++k)
      mass.push_back({{"phase", created[k]["phase"]},
                      {"through_walls", acc[k].walls},
                      {"cells_uncovered", acc[k].cells},
                      {"unaccounted", created[k]["mass"].get<double>() - acc[k].walls - acc[k].cells}});
    // What the wall faces put into the flow cells: conservative, no mass, and momentum and energy are the walls'
    // force and work; `flow_totals_change` less `totals.boundary_inflow` and this is what the cells covered or
    // uncovered moved (round-off when conservative).
    const std::vector<PhaseTotals> wall = rec.embedded_wall ? *rec.embedded_wall : sim.embedded_wall_exchange();
    j["embedded"] = {{"bodies", s.embedded.bodies.size()},
                     {"boundary_order", s.embedded.second_order ? 2 : 1},
                     {"conservative", s.embedded.conservative},
                     {"wall_exchange", totals_json(s, wall)},
                     {"ghost_and_solid_cut_cells",
                      rec.embedded_cells ? *rec.embedded_cells : static_cast<double>(sim.embedded().ghosts.size())},
                     {"flow_totals_change", change(false)},
                     {"mass", mass}};
  }
  for (const auto& [k, v] : rec.extra.items()) j[k] = v;
  io::write_file_atomically(dir / "summary.json", j.dump(2) + "\n");
}

// cosim check sets up a fluid state below this size to estimate its first step and snapshot size [bytes].
constexpr double kCheckSetUpLimit = 1024.0 * 1024.0 * 1024.0;

int run_fluid(const RunOptions& opt, const parallel::MpiSession& mpi) {
  if (!opt.coupled()) {  // a scene with coupling: and no solid: is not run as a fluid-only one
    try {
      app::refuse_coupling_without_solid(config::load_file(opt.scene_file, opt.overrides));
    } catch (const config::ConfigError& e) {
      spdlog::error("{}", e.what());
      return 2;
    }
  }
  if (opt.check) {  // the scene as a run reads it (its memory need included), nothing written
    const auto s = app::load_scene<FluidScene>(opt, load_fluid_scene);
    if (!s) return 2;
    double cells = 1;
    std::string shape;
    for (int d = 0; d < s->dim; ++d) {
      cells *= s->cells[d];
      shape += (d ? " x " : "") + std::to_string(s->cells[d]);
    }
    std::string names;
    for (const auto& ph : s->phases) names += (names.empty() ? "" : ", ") + ph.name;
    // The plan line cosim check prints; a state that fits easily is set up to tell the first step and the
    // size of a snapshot.
    const double state = static_cast<double>(estimated_state_bytes(*s));
    const double snapshot = 8.0 * cells * static_cast<double>(snapshot_values_per_cell(*s));
    nlohmann::json facts = nlohmann::json::object();
    std::string plan;
    if (state < kCheckSetUpLimit) {
      try {
        const double dt = make_simulation(*s)->stable_dt();
        facts["first_step"] = dt;
        plan = fmt::format(", first step {:.3g} s", dt);
        if (s->t_end > 0)
          plan += fmt::format(" (about {:.0f} steps to {:g} s at that step)", std::ceil(s->t_end / dt * (1 - 1e-12)),
                              s->t_end);
      } catch (const std::exception& e) {
        spdlog::error("{}: cannot set up the fluid solver: {}", opt.scene_name(), e.what());
        return 2;
      }
    } else {
      plan = fmt::format(", first step not estimated (the state is over {})", util::format_bytes(kCheckSetUpLimit));
    }
    plan += fmt::format(", snapshots about {} each", util::format_bytes(snapshot));
    if (s->coupled) plan += " (at the coupler's output times)";
    else if (!s->output_times.empty())
      plan += fmt::format(" ({} for {} of them)", util::format_bytes(snapshot * (s->output_times.size() + 1)),
                          s->output_times.size() + 1);
    std::string ranks_line;  // the layout on --ranks N, refused as the run would refuse it
    if (opt.check_ranks > 0) {
      try {
        ranks_line = rank_plan(*s, opt.check_ranks, state, facts);
      } catch (const std::exception& e) {
        spdlog::error("{}: {}", opt.scene_name(), e.what());
        return 2;
      }
    }
    std::cout << fmt::format(
        "fluid: {}D, {} cells ({:.4g}), {} phase(s) ({}){}, {} flux, state about {}{}{}{}\n", s->dim, shape, cells,
        s->num_phases(), names, s->exchange.dispersed ? ", the second dispersed" : "", to_string(s->flux),
        util::format_bytes(state),
        s->embedded.bodies.empty() ? "" : fmt::format(", {} embedded bod(ies)", s->embedded.bodies.size()),
        s->checkpoint.enabled() ? ", " + checkpoint::describe(s->checkpoint) : "", plan);
    if (!ranks_line.empty()) std::cout << "fluid " << ranks_line << "\n";
    if (opt.plan_facts) app::print_plan_facts(facts);
    return 0;
  }
  if (opt.coupled()) return run_fluid_coupled(opt, mpi);
  return run_fluid_blocks(opt, mpi);
}

}  // namespace cosim::fluid
