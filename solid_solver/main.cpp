// solid_solver SCENE.yaml --out DIR [--set key.path=value ...] [--quiet] [--threads N]
#include "common/app/run_options.h"
#include "common/app/threads.h"
#include "solid_solver/app/runner.h"

int main(int argc, char** argv) {
  cosim::app::prefer_passive_waiting(argv);
  cosim::app::RunOptions opt;
  if (auto rc = cosim::app::parse_command_line(argc, argv, "solid_solver",
                                               "explicit Lagrange hydro FEM with strength (standalone run)", opt))
    return *rc;
  return cosim::solid::run_solid(opt);
}
