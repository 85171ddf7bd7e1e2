// solid_solver SCENE.yaml --out DIR [--set key.path=value ...] [--quiet] [--threads N]
#include "common/app/run_options.h"
#include "common/app/threads.h"
#include "solid_solver/app/runner.h"

int main(int argc, char** argv) {
  cosim::app::prefer_passive_waiting(argv);
  cosim::parallel::MpiSession mpi(&argc, &argv);  // MPI when a launcher started this process
  cosim::app::RunOptions opt;
  if (auto rc = cosim::app::parse_command_line(argc, argv, "solid_solver",
                                               "explicit Lagrange hydro FEM with strength (standalone run)",
                                               "  solid_solver configs/solid_sedov_lulesh.yaml --out runs/sedov\n"
                                               "  solid_solver configs/solid_sedov_lulesh.yaml --out runs/sedov_30 "
                                               "--set 'solid.mesh.cells=[30,30,30]'\n"
                                               "  cosim run configs/shock_panel_2d.yaml     coupled to the fluid "
                                               "(cosim starts solid_solver)\n"
                                               "  mpirun -np 4 solid_solver configs/solid_sedov_lulesh.yaml --out "
                                               "runs/sedov   the mesh split over 4 ranks",
                                               opt))
    return *rc;
  return cosim::solid::run_solid(opt, mpi);
}
