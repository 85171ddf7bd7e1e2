// fluid_solver SCENE.yaml --out DIR [--set key.path=value ...] [--quiet] [--threads N]
#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "fluid_solver/app/runner.h"

int main(int argc, char** argv) {
  CLI::App app{"fluid_solver: multiphase DEM Godunov solver on a Cartesian mesh (standalone run)"};
  cosim::fluid::RunOptions opt;
  app.add_option("scene", opt.scene_file, "scene file (YAML)")->required();
  app.add_option("--out", opt.out_dir, "output directory (created if missing)")->required();
  app.add_option("--set", opt.overrides, "override a scene key: key.path=value (repeatable)");
  app.add_flag("--quiet,-q", opt.quiet, "no progress line");
  app.add_option("--threads", opt.threads, "OpenMP threads (default: scene value or all cores)");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_default_logger(spdlog::stderr_color_mt("fluid_solver"));  // stdout stays free for data
  spdlog::set_pattern("[fluid_solver] %^%l%$: %v");
  if (opt.quiet) spdlog::set_level(spdlog::level::warn);
  return cosim::fluid::run_fluid(opt);
}
