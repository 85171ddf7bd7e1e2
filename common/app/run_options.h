// Command line of a standalone solver run and the steps every run starts with.
//   NAME SCENE.yaml --out DIR [--set key.path=value ...] [--quiet] [--threads N] [--coupler EP --token T]
//                   [--restart SET] [--checkpoints ROOT]
//   NAME SCENE.yaml --check [--ranks N] [--set key.path=value ...]
#pragma once

#include <spdlog/spdlog.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/config/config.h"

namespace cosim::app {

struct RunOptions {
  std::string scene_file;
  std::filesystem::path out_dir;
  std::vector<std::string> overrides;
  bool quiet = false;
  int threads = 0;          // 0: scene value / OpenMP default
  std::string coupler;      // coupled run: the coupler's endpoint (the coupler owns the time loop); empty: standalone
  std::string token;        // per-run token of a coupled run (--token, else $COSIM_TOKEN)
  bool check = false;       // --check: validate the scene and the files it names, run nothing, write nothing
  bool plan_facts = false;  // --plan-facts (with --check, for cosim check): the plan's figures as JSON (plan_facts.h)
  int check_ranks = 0;      // --ranks N (with --check): the plan on N MPI ranks (layout, cells and memory per rank)
  std::filesystem::path restart;      // --restart SET: resume from this checkpoint set (checkpoint_sets.h)
  std::filesystem::path checkpoints;  // --checkpoints ROOT: where a fluid-only run writes its sets (OUT/checkpoints)
  bool coupled() const { return !coupler.empty(); }
  // The scene as messages name it: the user's file, also when the solver reads cosim run's copy.
  std::string scene_name() const { return config::scene_name(scene_file); }
};

// Parses the command line and sets up logging on stderr as "[name] level: message". Returns an exit
// code when the process should stop now (--help: 0, bad arguments: 2), nothing otherwise. `examples` end --help.
std::optional<int> parse_command_line(int argc, char** argv, const std::string& name, const std::string& description,
                                      const std::string& examples, RunOptions& opt);

// Loads the scene with `load(file, overrides)` and applies --threads; a configuration error is
// logged ("file:line: key: expected ...") and gives nothing (the caller exits with code 2).
template <class Scene, class Load>
std::optional<Scene> load_scene(const RunOptions& opt, Load&& load) {
  try {
    Scene scene = load(opt.scene_file, opt.overrides);
    if (opt.threads > 0) scene.threads = opt.threads;
    return scene;
  } catch (const config::ConfigError& e) {
    spdlog::error("{}", e.what());
    return std::nullopt;
  }
}

// Creates the output directory; logs and returns false when that is impossible.
bool make_output_directory(const std::filesystem::path& dir);

// $COSIM_TOKEN, where cosim run passes the per-run token to the processes it starts ("" when unset).
std::string token_from_environment();

}  // namespace cosim::app
