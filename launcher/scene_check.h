// The whole scene checked before anything starts: each of the run's own programs (coupler, fluid_solver,
// solid_solver next to cosim) reads it with --check, as its run would, in the order that names the root cause
// first (the coupling section, which the solvers' time keys depend on, before the solvers' sections). A program
// that the scene or the command line replaces is not asked (it need not know --check).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace cosim::launcher {

struct SceneRefusal {
  std::string program;  // "coupler", "fluid_solver", "solid_solver"
  int exit_code = 0;
  std::string message;  // what it printed
};

struct SceneCheck {
  std::string scene;
  std::vector<std::string> overrides;
  bool coupled = false;
  std::filesystem::path bin_dir;
  bool check_fluid = true, check_solid = true, check_coupler = true;  // false: a replaced program (or none)
  bool solid_only = false;                                            // a scene without fluid:
  int fluid_ranks = 1;  // the fluid's MPI ranks: its plan states their layout and share (fluid_solver --ranks)
  int solid_ranks = 1;  // the solid's: its plan states their parts (solid_solver --ranks)
};

// The first program that refuses the scene, with its message; nothing when all accept it. `plan` gets what each
// program that accepts it says it will do (one line each: cells, elements, memory, ...), `facts` the figures of
// its plan by program name (common/app/plan_facts.h).
std::optional<SceneRefusal> check_scene(const SceneCheck& c, std::vector<std::string>* plan = nullptr,
                                        nlohmann::json* facts = nullptr);

// The coupled cycle the programs' facts imply: the first cycle's step (the smallest of the fluid's first step, the
// solid's stable step times its substeps and coupling.time.dt_max, naming which one limits) and the cycles to the end
// time at that step. Empty where no step is known.
std::string coupled_estimate(const nlohmann::json& facts);

// Runs argv (no shell) with stdout and stderr captured; its exit code (128 + N when killed by signal N), -1 when it
// could not be started. Killed after `timeout` seconds.
int run_captured(const std::vector<std::string>& argv, std::string& output, double timeout);

}  // namespace cosim::launcher
