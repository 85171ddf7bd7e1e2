// solid_solver SCENE.yaml --out DIR [--set key.path=value ...] [--quiet] [--threads N]
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "solid_solver/app/runner.h"

int main(int argc, char** argv) {
  CLI::App app{"solid_solver: explicit Lagrange hydro FEM with strength (standalone run)"};
  cosim::solid::RunOptions opt;
  app.add_option("scene", opt.scene_file, "scene file (YAML)")->required();
  app.add_option("--out", opt.out_dir, "output directory (created if missing)")->required();
  app.add_option("--set", opt.overrides, "override a scene key: key.path=value (repeatable)");
  app.add_flag("--quiet,-q", opt.quiet, "no progress line");
  app.add_option("--threads", opt.threads, "OpenMP threads (default: scene value or all cores)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  spdlog::set_pattern("[solid_solver] %^%l%$: %v");
  if (opt.quiet) spdlog::set_level(spdlog::level::warn);
  return cosim::solid::run_solid(opt);
}
